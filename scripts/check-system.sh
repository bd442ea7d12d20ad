#!/bin/sh
# Checks that the set-up (scripts/setup.sh) left the system's package manager and Pythons working:
#
#   scripts/check-system.sh [--pvpython PVPYTHON]
#
# - apt-get check succeeds and dpkg --audit reports nothing;
# - every package dpkg lists is installed (ii) or removed with its configuration kept (rc);
# - the packages an earlier set-up overwrote (python3-vtk9, ParaView's) have their own files;
# - apt can install a package: `hello` is installed and purged again as root (left alone when it
#   was there before), its installation simulated otherwise;
# - /usr/bin/python3 imports Debian's VTK, and PVPYTHON (when given) imports paraview.simple;
# - the set-up passes no --force-* option to dpkg.
# Prints each failure and exits 1 when there is one.
set -u
root="$(cd "$(dirname "$0")/.." && pwd)"
pvpython=""
[ "${1:-}" = --pvpython ] && pvpython="${2:-}"

failures=0
fail() { printf 'check-system: FAIL: %s\n' "$*" >&2; failures=$((failures + 1)); }
ok() { printf 'check-system: ok: %s\n' "$*" >&2; }
installed() { [ "$(dpkg-query -W -f='${db:Status-Status}' "$1" 2>/dev/null)" = installed ]; }

out="$(apt-get check 2>&1)" && ok "apt-get check" || fail "apt-get check: $out"

out="$(dpkg --audit 2>&1)"
[ -z "$out" ] && ok "dpkg --audit" || fail "dpkg --audit: $out"

out="$(dpkg-query -W -f='${db:Status-Abbrev}${Package}\n' | grep -v -e '^ii ' -e '^rc ')"
[ -z "$out" ] && ok "every package is ii or rc" || fail "packages in other states: $out"

for p in python3-vtk9 python3-paraview paraview paraview-dev; do
  installed "$p" || continue
  out="$(dpkg --verify "$p" 2>&1)"
  [ -z "$out" ] && ok "dpkg --verify $p" || fail "dpkg --verify $p: $out"
done

if [ "$(id -u)" -eq 0 ] && ! installed hello; then
  if out="$(DEBIAN_FRONTEND=noninteractive apt-get install -y -q hello 2>&1)" \
      && /usr/bin/hello >/dev/null \
      && out="$(DEBIAN_FRONTEND=noninteractive apt-get purge -y -q hello 2>&1)"; then
    ok "apt-get install hello, then purge"
  else
    fail "apt-get install/purge hello: $(printf '%s' "$out" | tail -n 5)"
  fi
else
  out="$(apt-get install -s -q hello 2>&1)" && ok "apt-get install -s hello" \
    || fail "apt-get install -s hello: $(printf '%s' "$out" | tail -n 5)"
fi

out="$(cd / && /usr/bin/python3 -c 'import vtk; print(vtk.vtkVersion.GetVTKVersion())' 2>&1)" \
  && ok "/usr/bin/python3 imports VTK $out" || fail "/usr/bin/python3 -c 'import vtk': $out"

if [ -n "$pvpython" ]; then
  out="$(cd / && "$pvpython" -c 'from paraview.simple import *; print(GetParaViewVersion())' 2>&1)" \
    && ok "$pvpython imports paraview.simple $out" || fail "$pvpython: $(printf '%s' "$out" | tail -n 5)"
fi

# Every script of the set-up and the entry script (this one names the option it looks for).
out="$(grep -n -e '--force-' "$root/splat" $(ls "$root"/scripts/*.sh | grep -v check-system.sh))"
[ -z "$out" ] && ok "no --force-* options in the set-up" || fail "--force-* in the set-up: $out"

[ "$failures" -eq 0 ] || exit 1
