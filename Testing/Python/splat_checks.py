"""Checks shared by the plugin tests: each check prints ok/FAIL, and the test's exit status is
non-zero when any failed."""

import os
import traceback

failures = []


def check(condition, message):
    print("%s %s" % ("ok  " if condition else "FAIL", message), flush=True)
    if not condition:
        failures.append(message)
    return condition


def info_value(proxy, info_name):
    """Value of an information-only property, read from the server-side VTK object."""
    proxy.UpdatePropertyInformation()
    prop = proxy.GetProperty(info_name)
    if prop is None or prop.GetNumberOfElements() == 0:
        return None
    return prop.GetElement(0)


def exit_status():
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    print("all checks passed")
    return 0


def load_plugin(path, ns):
    """Loads the plugin at PATH on the client, its constructors into the namespace NS (and
    paraview.simple); a missing file or a plugin that does not load is a failed check. Returns
    whether it loaded."""
    if not check(os.path.isfile(path), "plugin file exists: %s" % path):
        return False
    from paraview import simple
    try:
        simple.LoadPlugin(path, remote=False, ns=ns)
    except Exception as error:  # a plugin that does not load fails the test
        return check(False, "LoadPlugin: %s" % error)
    return check(True, "LoadPlugin")


def run_tests(tests):
    """Runs each callable of TESTS, an exception counting as a failed check (the others still
    run); returns the test's exit status."""
    for test in tests:
        try:
            test()
        except Exception:
            traceback.print_exc()
            check(False, "exception (see above)")
    return exit_status()
