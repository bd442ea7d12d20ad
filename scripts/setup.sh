#!/usr/bin/env bash
# Idempotent set-up of a Debian 12 (bookworm) machine for building and testing Splat.
#
#   scripts/setup.sh            install what is missing; does nothing when all is present
#   SPLAT_DEPS_DIR=DIR          where the python3-paraview and python3-vtk9 packages are cached,
#                               and python3-paraview unpacked
#                               (default: build/deps in the repository; build/ is ignored by git)
#
# 1. Installs the missing apt packages (sudo only when not root).
# 2. ParaView's Python modules: Debian's python3-paraview conflicts with python3-vtk9 (which
#    libvtk9-dev needs). find_package(ParaView) checks that its imported targets' files exist:
#    /usr/bin/pvpython and the extension modules vtkmodules/*.so and paraview/modules/*.so, none
#    of which python3-vtk9 has (VTK 9.1's are *.cpython-311-x86_64-linux-gnu.so). So the package
#    is downloaded and force-installed with dpkg --force-conflicts --force-overwrite, and a copy
#    is unpacked under SPLAT_DEPS_DIR for pvpython's PYTHONPATH (see /work/shared/ENVIRONMENT.md).
# 3. The two packages do share 38 pure-Python files (vtk.py, vtkmodules/__init__.py, all.py,
#    util/, ...): the force-install overwrites VTK 9.1's, which breaks /usr/bin/python3's
#    `import vtk`. python3-vtk9's own .deb is then installed again over them, so that the system
#    VTK's Python works and dpkg's database says which package owns each file. pvpython does not
#    need ParaView's copies: its PYTHONPATH holds the unpacked package.
# 4. The converters the capture format tests compare the readers against (npm, pinned):
#    PlayCanvas's splat-transform and GaussianSplats3D (.ksplat), under
#    SPLAT_DEPS_DIR/capture-tools; skipped with a note where the machine has no npm (those tests
#    then skip).
# While python3-paraview is force-installed apt refuses to install anything else, so when a
# package is missing it is removed first (dpkg --remove; the shared files stay with
# python3-vtk9), then everything is installed and steps 2 and 3 run again.
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
  # the compressed 3DGS capture formats: .spz (zlib, zstd), .sog (minizip, WebP), glTF (jsoncpp)
  zlib1g-dev libzstd-dev libminizip-dev libwebp-dev libjsoncpp-dev
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
  if [ "$(pkg_status python3-paraview)" = installed ]; then
    log "removing the force-installed python3-paraview so that apt accepts new installs"
    quietly "${SUDO[@]}" dpkg --remove python3-paraview
  fi
  apt_update
  "${APT[@]}" install --no-install-recommends "${missing[@]}" >&2
fi

# --- 2. python3-paraview --------------------------------------------------------------------
pv_version="$(pkg_version paraview)"
[ -n "$pv_version" ] || die "paraview is not installed"

# fetch_deb PACKAGE VERSION: sets `deb` to PACKAGE=VERSION's .deb, from apt's cache or
# $DEPS_DIR, else downloaded into $DEPS_DIR.
deb=""
find_cached_deb() {
  local f
  for f in /var/cache/apt/archives/"$1"_*.deb "$DEPS_DIR/$1"_*.deb; do
    if [ -f "$f" ] && [ "$(dpkg-deb -f "$f" Version 2>/dev/null)" = "$2" ]; then
      deb="$f"
      return 0
    fi
  done
  return 1
}
fetch_deb() {
  deb=""
  find_cached_deb "$1" "$2" && return 0
  mkdir -p "$DEPS_DIR"
  local tmp
  tmp="$(mktemp -d "$DEPS_DIR/download.XXXXXX")"
  local sandbox=()
  # As root, apt drops to the _apt user for downloads, which cannot write to our directory.
  [ "$(id -u)" -eq 0 ] && sandbox=(-o APT::Sandbox::User=root)
  log "downloading $1=$2"
  if ! (cd "$tmp" && apt-get -q "${sandbox[@]}" download "$1=$2" >&2); then
    apt_update
    (cd "$tmp" && apt-get -q "${sandbox[@]}" download "$1=$2" >&2) \
      || { rm -rf "$tmp"; die "cannot download $1=$2"; }
  fi
  rm -f "$DEPS_DIR/$1"_*.deb
  mv "$tmp/$1"_*.deb "$DEPS_DIR"/
  rm -rf "$tmp"
  find_cached_deb "$1" "$2" || die "$1=$2 download not found"
}

need_deb=0
[ "$(pkg_status python3-paraview)" = installed ] \
  && [ "$(pkg_version python3-paraview)" = "$pv_version" ] || need_deb=1
[ "$(cat "$PV_PY_DIR/.version" 2>/dev/null || true)" = "$pv_version" ] || need_deb=1

if [ "$need_deb" -eq 1 ]; then
  fetch_deb python3-paraview "$pv_version"
  pv_deb="$deb"

  if [ "$(pkg_status python3-paraview)" != installed ] \
     || [ "$(pkg_version python3-paraview)" != "$pv_version" ]; then
    log "force-installing python3-paraview over the conflict with python3-vtk9"
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

# --- 3. python3-vtk9's own pure-Python files back over ParaView's ----------------------------
vtk_py_init=/usr/lib/python3/dist-packages/vtkmodules/__init__.py
if [ "$(dpkg-query -S "$vtk_py_init" 2>/dev/null | cut -d: -f1)" != python3-vtk9 ]; then
  vtk_version="$(pkg_version python3-vtk9)"
  [ -n "$vtk_version" ] || die "python3-vtk9 is not installed"
  fetch_deb python3-vtk9 "$vtk_version"
  log "installing python3-vtk9's own files again over python3-paraview's"
  quietly "${SUDO[@]}" dpkg -i --force-conflicts --force-overwrite "$deb"
  /usr/bin/python3 -c "import vtk" >/dev/null 2>&1 \
    || die "/usr/bin/python3 still cannot import vtk after reinstalling python3-vtk9"
fi

# --- 4. The converters of the capture format tests -----------------------------------------
CAPTURE_TOOLS=(@playcanvas/splat-transform@3.7.0 @mkkellogg/gaussian-splats-3d@0.4.7 three@0.160.0)
TOOLS_DIR="$DEPS_DIR/capture-tools"
if [ "$(cat "$TOOLS_DIR/.version" 2>/dev/null || true)" != "${CAPTURE_TOOLS[*]}" ]; then
  if command -v npm >/dev/null 2>&1; then
    log "installing ${CAPTURE_TOOLS[*]} into $TOOLS_DIR"
    rm -rf "$TOOLS_DIR"
    mkdir -p "$TOOLS_DIR"
    quietly npm install --prefix "$TOOLS_DIR" --no-audit --no-fund --no-save "${CAPTURE_TOOLS[@]}"
    printf '%s\n' "${CAPTURE_TOOLS[*]}" > "$TOOLS_DIR/.version"
  else
    log "npm not found: the capture format round-trip tests will be skipped"
  fi
fi
