#!/usr/bin/env bash
# Idempotent set-up of a Debian 12 (bookworm) machine for building and testing Splat.
#
#   scripts/setup.sh            install what is missing; does nothing when all is present
#   SPLAT_DEPS_DIR=DIR          where the python3-paraview package is cached and unpacked
#                               (default: build/deps in the repository; build/ is ignored by git)
#
# 1. Installs the missing apt packages (sudo only when not root).
# 2. ParaView's Python modules: Debian's python3-paraview conflicts with python3-vtk9 (which
#    libvtk9-dev needs) although their files do not really collide. find_package(ParaView) needs
#    python3-paraview's files, so the package is downloaded and force-installed with
#    dpkg --force-conflicts --force-overwrite, and a copy is unpacked under SPLAT_DEPS_DIR for
#    pvpython's PYTHONPATH (see /work/shared/ENVIRONMENT.md and scripts/paraview-env.sh).
#    While python3-paraview is force-installed apt refuses to install anything else, so when a
#    package is missing it is removed first (and python3-vtk9, whose pure-Python files it
#    overwrote, reinstalled), then everything is installed and it is forced in again.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DEPS_DIR="${SPLAT_DEPS_DIR:-$ROOT/build/deps}"
PV_PY_DIR="$DEPS_DIR/python3-paraview"

PACKAGES=(
  # toolchain
  cmake g++ gcc make pkg-config libgtest-dev python3
  # VTK 9.1, OpenVDB, OpenImageIO, GLM, Eigen
  libvtk9-dev python3-vtk9 libopenvdb-dev libboost-iostreams-dev libglm-dev libeigen3-dev
  libopenimageio-dev libopencv-core-dev openimageio-tools
  # offscreen OpenGL (Mesa llvmpipe) under a virtual X server
  xvfb xauth libgl1-mesa-dri mesa-utils
  # ParaView 5.11 and what its CMake package asks for
  paraview paraview-dev qtbase5-dev qttools5-dev libqt5opengl5-dev libqt5svg5-dev
  # xmlpatterns: the plugin build turns its server-manager XML into ParaView help pages
  qtxmlpatterns5-dev-tools
  # real data used by the examples and tests
  mricron-data libcgal-demo
)

log() { printf 'setup: %s\n' "$*" >&2; }
# Runs a command with its output kept in $DEPS_DIR/setup.log; shows the log's end on failure.
quietly() {
  mkdir -p "$DEPS_DIR"
  if ! "$@" >>"$DEPS_DIR/setup.log" 2>&1; then
    tail -n 40 "$DEPS_DIR/setup.log" >&2
    die "failed: $*"
  fi
}
die() { printf 'setup: error: %s\n' "$*" >&2; exit 1; }

SUDO=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || die "not root and sudo is not available"
  SUDO=(sudo)
fi
APT=("${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -y -q
     -o Dpkg::Options::=--force-confdef -o Dpkg::Options::=--force-confold)

# Prints "installed" for an installed package, nothing otherwise.
pkg_status() { dpkg-query -W -f='${db:Status-Status}' "$1" 2>/dev/null || true; }
pkg_version() { dpkg-query -W -f='${Version}' "$1" 2>/dev/null || true; }

apt_updated=0
apt_update() {
  if [ "$apt_updated" -eq 0 ]; then
    log "apt-get update"
    # Unreachable third-party sources only warn; a real failure shows up at install time.
    "${APT[@]}" update >&2 || log "apt-get update reported errors; continuing"
    apt_updated=1
  fi
}

# --- 1. apt packages ------------------------------------------------------------------------
missing=()
while read -r name status; do
  [ "$status" = installed ] || missing+=("$name")
done < <(for p in "${PACKAGES[@]}"; do printf '%s %s\n' "$p" "$(pkg_status "$p")"; done)

if [ "${#missing[@]}" -gt 0 ]; then
  log "installing missing packages: ${missing[*]}"
  reinstall_vtk_python=0
  if [ "$(pkg_status python3-paraview)" = installed ]; then
    log "removing the force-installed python3-paraview so that apt accepts new installs"
    quietly "${SUDO[@]}" dpkg --remove python3-paraview
    [ "$(pkg_status python3-vtk9)" = installed ] && reinstall_vtk_python=1
  fi
  apt_update
  "${APT[@]}" install --no-install-recommends "${missing[@]}" >&2
  if [ "$reinstall_vtk_python" -eq 1 ]; then
    # python3-paraview had overwritten python3-vtk9's pure-Python files; put them back.
    "${APT[@]}" install --no-install-recommends --reinstall python3-vtk9 >&2
  fi
fi

# --- 2. python3-paraview --------------------------------------------------------------------
pv_version="$(pkg_version paraview)"
[ -n "$pv_version" ] || die "paraview is not installed"

# The cached .deb of python3-paraview matching the installed paraview, downloaded if needed.
pv_deb=""
find_cached_deb() {
  pv_deb=""
  local f
  for f in "$DEPS_DIR"/python3-paraview_*.deb; do
    [ -f "$f" ] || continue
    if [ "$(dpkg-deb -f "$f" Version 2>/dev/null)" = "$pv_version" ]; then
      pv_deb="$f"
      return 0
    fi
  done
  return 1
}

download_deb() {
  mkdir -p "$DEPS_DIR"
  local tmp
  tmp="$(mktemp -d "$DEPS_DIR/download.XXXXXX")"
  local sandbox=()
  # As root, apt drops to the _apt user for downloads, which cannot write to our directory.
  [ "$(id -u)" -eq 0 ] && sandbox=(-o APT::Sandbox::User=root)
  log "downloading python3-paraview=$pv_version"
  if ! (cd "$tmp" && apt-get -q "${sandbox[@]}" download "python3-paraview=$pv_version" >&2); then
    apt_update
    (cd "$tmp" && apt-get -q "${sandbox[@]}" download "python3-paraview=$pv_version" >&2) \
      || { rm -rf "$tmp"; die "cannot download python3-paraview=$pv_version"; }
  fi
  rm -f "$DEPS_DIR"/python3-paraview_*.deb
  mv "$tmp"/python3-paraview_*.deb "$DEPS_DIR"/
  rm -rf "$tmp"
}

need_deb=0
[ "$(pkg_status python3-paraview)" = installed ] \
  && [ "$(pkg_version python3-paraview)" = "$pv_version" ] || need_deb=1
[ "$(cat "$PV_PY_DIR/.version" 2>/dev/null || true)" = "$pv_version" ] || need_deb=1

if [ "$need_deb" -eq 1 ]; then
  find_cached_deb || { download_deb; find_cached_deb || die "python3-paraview download not found"; }

  if [ "$(pkg_status python3-paraview)" != installed ] \
     || [ "$(pkg_version python3-paraview)" != "$pv_version" ]; then
    log "force-installing python3-paraview (conflicts with python3-vtk9 on paper only)"
    quietly "${SUDO[@]}" dpkg -i --force-conflicts --force-overwrite "$pv_deb"
  fi

  if [ "$(cat "$PV_PY_DIR/.version" 2>/dev/null || true)" != "$pv_version" ]; then
    log "unpacking python3-paraview into $PV_PY_DIR"
    rm -rf "$PV_PY_DIR"
    mkdir -p "$PV_PY_DIR"
    dpkg-deb -x "$pv_deb" "$PV_PY_DIR"
    printf '%s\n' "$pv_version" > "$PV_PY_DIR/.version"
  fi
fi

[ -d "$PV_PY_DIR/usr/lib/python3/dist-packages/paraview" ] \
  || die "unpacked python3-paraview is incomplete: $PV_PY_DIR"
