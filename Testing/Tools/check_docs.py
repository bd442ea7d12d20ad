"""The README and docs/ as a newcomer meets them: every relative link and image resolves, the
README's Python quick starts run as written and its C++ quick start compiles.

  check_docs.py links ROOT
      every [text](target) and ![alt](target) of ROOT/README.md and ROOT/docs/*.md that is not a
      URL names an existing file (anchors are not checked).
  check_docs.py run ROOT HEADING INTERPRETER [FROM=TO ...]
      runs the README's ```python block under the heading HEADING with INTERPRETER (python3,
      pvpython), in a scratch folder, after replacing each FROM by TO (a plugin's path or a file
      name that depends on the build); exits 125 (skipped) when a TO that is an absolute path
      does not exist.
  check_docs.py cxx ROOT HEADING OUTPUT
      writes the README's ```cpp blocks under the heading HEADING to OUTPUT as one translation
      unit: their #include lines, the header of each other VTK class they name (the blocks leave
      the usual ones out), and their statements as the body of one function.
"""
import os
import re
import subprocess
import sys
import tempfile

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def markdown_files(root):
    docs = os.path.join(root, "docs")
    return [os.path.join(root, "README.md")] + sorted(
        os.path.join(docs, name) for name in os.listdir(docs) if name.endswith(".md"))


def check_links(root):
    broken = []
    count = 0
    for path in markdown_files(root):
        text = open(path, encoding="utf-8").read()
        # Links inside fenced code are code, not links.
        text = re.sub(r"```.*?```", "", text, flags=re.S)
        for target in LINK.findall(text):
            if re.match(r"[a-z]+:", target) or target.startswith("#"):
                continue
            count += 1
            resolved = os.path.normpath(os.path.join(os.path.dirname(path), target.split("#")[0]))
            if not os.path.exists(resolved):
                broken.append("%s: %s" % (os.path.relpath(path, root), target))
    print("%d relative links and images checked" % count)
    for line in broken:
        print("BROKEN: " + line)
    return 1 if broken or count == 0 else 0


def blocks(root, heading, language):
    text = open(os.path.join(root, "README.md"), encoding="utf-8").read()
    section = text.split("\n## " + heading + "\n", 1)
    if len(section) != 2:
        sys.exit("no heading '## %s' in the README" % heading)
    found = re.findall(r"```" + language + r"\n(.*?)```", section[1].split("\n## ", 1)[0], re.S)
    if not found:
        sys.exit("no %s block under '## %s'" % (language, heading))
    return found


def python_block(root, heading):
    return blocks(root, heading, "python")[0]


def write_cxx(root, heading, output):
    code = "".join(blocks(root, heading, "cpp"))
    includes = re.findall(r"^#include .*$", code, re.M)
    statements = re.sub(r"^#include .*\n", "", code, flags=re.M).lstrip("\n")
    named = sorted(set(re.findall(r"\bvtk[A-Z]\w*", statements)))
    included = set(re.findall(r'"(vtk\w+)\.h"', code))
    with open(output, "w", encoding="utf-8") as f:
        f.write("// The README's '## %s' blocks (Testing/Tools/check_docs.py cxx).\n" % heading)
        f.write("\n".join(includes + ['#include "%s.h"' % name for name in named
                                      if name not in included]))
        f.write("\n\nvoid ReadmeQuickStart()\n{\n%s}\n" % statements)
    return 0


def run_block(root, heading, interpreter, replacements):
    code = python_block(root, heading)
    for pair in replacements:
        old, new = pair.split("=", 1)
        if old not in code:
            sys.exit("the block under '## %s' no longer holds '%s'" % (heading, old))
        if os.path.isabs(new) and not os.path.exists(new):
            print("%s is absent: skipped" % new)
            return 125
        code = code.replace(old, new)
    with tempfile.TemporaryDirectory() as scratch:
        script = os.path.join(scratch, "quick_start.py")
        with open(script, "w", encoding="utf-8") as f:
            f.write(code)
        print("running the README's block under '## %s':\n%s" % (heading, code))
        return subprocess.call([interpreter, script], cwd=scratch)


def main(argv):
    if len(argv) >= 3 and argv[1] == "links":
        return check_links(argv[2])
    if len(argv) >= 5 and argv[1] == "run":
        return run_block(argv[2], argv[3], argv[4], argv[5:])
    if len(argv) == 5 and argv[1] == "cxx":
        return write_cxx(argv[2], argv[3], argv[4])
    sys.exit(__doc__)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
