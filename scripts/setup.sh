#!/usr/bin/env bash
# Idempotent set-up of a Debian 12 (bookworm) machine for building and testing Splat, or of the
# Debian 13 (trixie) root of its second test leg.
#
#   scripts/setup.sh [vtk|paraview|test]
#       vtk       what the VTK modules, the examples and the Python package need (./splat demo,
#                 bench, report, python, build vtk)
#       paraview  vtk, plus ParaView 5.11 for the plugin (./splat build paraview|all)
#       docs      paraview, plus what ./splat docs screenshots runs: xwd (x11-apps) and xdotool
#       gpu-check vtk, plus what scripts/gpu-check.sh needs to pack (a Mesa build: meson, the X and
#                 GL headers) and to verify (debootstrap) its archive
#       test      paraview, plus debootstrap (the Debian 13 test leg, scripts/debian-root.sh) and
#                 the converters the capture format tests compare against (./splat test; the
#                 default)
#   SPLAT_DEPS_DIR=DIR   where the private ParaView files go (default: build/deps in the
#                        repository; build/ is ignored by git)
#
# The set-up leaves apt and dpkg consistent: it installs packages with apt-get only and forces
# nothing (scripts/check-system.sh tests that; docs/setup.md says why it is done this way).
#
# ParaView: find_package(ParaView) checks that the files of its Python targets exist (pvpython,
# the extension modules under dist-packages/vtkmodules and paraview/modules), which Debian ships
# in python3-paraview. That package conflicts with python3-vtk9, which the system VTK's Python
# (and Splat's Python package) needs, so it is not installed. Instead:
#   1. its .deb is downloaded (apt-get download) and unpacked under SPLAT_DEPS_DIR;
#   2. a private copy of ParaView's CMake package is made there, whose imported targets point at
#      the system's files in /usr, except the Python ones, which point at the unpacked package;
#   3. SPLAT_DEPS_DIR/bin/pvpython runs the unpacked pvpython with its own modules first.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DEPS_DIR="${SPLAT_DEPS_DIR:-$ROOT/build/deps}"
PV_PY_DIR="$DEPS_DIR/python3-paraview"
PV_CMAKE_DIR="$DEPS_DIR/paraview-cmake"
PROFILE="${1:-test}"

VTK_PACKAGES=(
  # toolchain
  cmake g++ gcc make pkg-config libgtest-dev python3
  # VTK 9.1, OpenVDB, OpenImageIO, GLM, Eigen
  libvtk9-dev python3-vtk9 libopenvdb-dev libboost-iostreams-dev libglm-dev libeigen3-dev
  libopenimageio-dev libopencv-core-dev openimageio-tools
  # the compressed 3DGS capture formats: .spz (zlib, zstd), .sog (minizip, WebP), glTF (jsoncpp)
  zlib1g-dev libzstd-dev libminizip-dev libwebp-dev libjsoncpp-dev
  # offscreen OpenGL (Mesa llvmpipe) under a virtual X server
  xvfb xauth libgl1-mesa-dri mesa-utils
  # real data used by the examples and tests
  mricron-data libcgal-demo
)
# ParaView and the Qt its CMake package asks for: Debian 12's ParaView 5.11 is built with Qt 5,
# Debian 13's 5.13 (the second test leg, scripts/debian-root.sh) with Qt 6.
PARAVIEW_PACKAGES=(paraview paraview-dev)
if [ "$(. /etc/os-release && echo "${VERSION_CODENAME:-}")" = bookworm ]; then
  PARAVIEW_PACKAGES+=(qtbase5-dev qttools5-dev libqt5opengl5-dev libqt5svg5-dev
    # xmlpatterns: the plugin build turns its server-manager XML into ParaView help pages
    qtxmlpatterns5-dev-tools)
else
  PARAVIEW_PACKAGES+=(qt6-base-dev qt6-5compat-dev qt6-tools-dev qt6-svg-dev)
fi
DOCS_PACKAGES=(x11-apps xdotool)
TEST_PACKAGES=(
  # the Debian 13 root of the second test leg (scripts/debian-root.sh)
  debootstrap
)
# scripts/gpu-check.sh: Mesa's build (the X server's GLX in the archive) and the clean root.
# Not libexpat1-dev, which Mesa also needs: VTK's packages bring it, and installing it by name
# upgrades libexpat1, whose reparse deferral (2.5.0-1+deb12u2 on) breaks the XML that
# ParaView 5.11 sends between MPI ranks (SplatPlugin.RepresentationsMPI fails).
GPU_CHECK_PACKAGES=(
  meson ninja-build python3-mako bison flex libdrm-dev libx11-dev libxext-dev libxfixes-dev
  libx11-xcb-dev libxcb-glx0-dev libxcb-dri2-0-dev libxcb-dri3-dev libxcb-present-dev
  libxcb-shm0-dev libxcb-randr0-dev libxshmfence-dev libxxf86vm-dev libxrandr-dev
  libglvnd-dev x11-xkb-utils debootstrap
)
CAPTURE_TOOLS=(@playcanvas/splat-transform@3.7.0 @mkkellogg/gaussian-splats-3d@0.4.7 three@0.160.0)

log() { printf 'setup: %s\n' "$*" >&2; }
die() { printf 'setup: error: %s\n' "$*" >&2; exit 1; }
# Runs a command with its output kept in $DEPS_DIR/setup.log; shows the log's end on failure.
quietly() {
  mkdir -p "$DEPS_DIR"
  if ! "$@" >>"$DEPS_DIR/setup.log" 2>&1; then
    tail -n 40 "$DEPS_DIR/setup.log" >&2
    die "failed: $*"
  fi
}

case "$PROFILE" in
  vtk) packages=("${VTK_PACKAGES[@]}") ;;
  paraview) packages=("${VTK_PACKAGES[@]}" "${PARAVIEW_PACKAGES[@]}") ;;
  docs) packages=("${VTK_PACKAGES[@]}" "${PARAVIEW_PACKAGES[@]}" "${DOCS_PACKAGES[@]}") ;;
  test) packages=("${VTK_PACKAGES[@]}" "${PARAVIEW_PACKAGES[@]}" "${TEST_PACKAGES[@]}") ;;
  gpu-check) packages=("${VTK_PACKAGES[@]}" "${GPU_CHECK_PACKAGES[@]}") ;;
  *) die "unknown profile '$PROFILE' (vtk, paraview, docs, gpu-check or test)" ;;
esac

SUDO=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || die "not root and sudo is not available"
  SUDO=(sudo)
fi
APT=("${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -y -q)

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

# --- apt packages -----------------------------------------------------------------------------
if [ "$(pkg_status python3-paraview)" = installed ]; then
  if [ "$(pkg_status python3-vtk9)" = installed ]; then
    # Only a forced install (earlier versions of this script did one) puts the two conflicting
    # packages side by side, and apt then refuses every install. python3-paraview is removed;
    # the files the two share belong to python3-vtk9 since then and are reinstalled to be sure.
    log "repairing apt: removing python3-paraview, force-installed next to python3-vtk9" \
        "by an earlier set-up (Splat uses a private copy of it)"
    quietly "${SUDO[@]}" dpkg --remove python3-paraview
    apt_update
    quietly "${APT[@]}" install --reinstall python3-vtk9
  else
    die "python3-paraview is installed; it conflicts with python3-vtk9, which Splat needs." \
        "Remove it (apt-get remove python3-paraview): Splat's ParaView build uses a private copy."
  fi
fi

missing=()
for p in "${packages[@]}"; do
  [ "$(pkg_status "$p")" = installed ] || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  log "installing missing packages: ${missing[*]}"
  apt_update
  "${APT[@]}" install --no-install-recommends "${missing[@]}" >&2
fi

case "$PROFILE" in vtk|gpu-check) exit 0 ;; esac

# --- ParaView's Python package, unpacked --------------------------------------------------------
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

stamp() { cat "$1/.version" 2>/dev/null || true; }

if [ "$(stamp "$PV_PY_DIR")" != "$pv_version" ]; then
  fetch_deb python3-paraview "$pv_version"
  log "unpacking python3-paraview into $PV_PY_DIR"
  rm -rf "$PV_PY_DIR"
  mkdir -p "$PV_PY_DIR"
  dpkg-deb -x "$deb" "$PV_PY_DIR"
  printf '%s\n' "$pv_version" > "$PV_PY_DIR/.version"
fi
pv_site="$PV_PY_DIR/usr/lib/python3/dist-packages"
[ -f "$pv_site/paraview/simple.py" ] && [ -x "$PV_PY_DIR/usr/bin/pvpython" ] \
  || die "unpacked python3-paraview is incomplete: $PV_PY_DIR"

# (grep reads the whole list: stopping early would fail dpkg's write under pipefail)
pv_config="$(dpkg -L paraview-dev | grep '/cmake/paraview-[0-9.]*/paraview-config.cmake$')" \
  || die "paraview-dev has no paraview-config.cmake"
pv_config="${pv_config%%$'\n'*}"
pv_cmake_src="$(dirname "$pv_config")"
# ParaView's libraries, /usr/lib/<multiarch>
pv_libdir="$(dirname "$(dirname "$pv_cmake_src")")"

# pvpython. ParaView's libraries are named by their /usr path so that VTK's search for its
# Python modules (relative to the library) does not put VTK 9.1's, in /usr/lib/python3, first.
mkdir -p "$DEPS_DIR/bin"
cat > "$DEPS_DIR/bin/pvpython.tmp" <<EOF
#!/bin/sh
# ParaView $pv_version's pvpython from the unpacked python3-paraview (written by scripts/setup.sh).
PYTHONPATH="$pv_site\${PYTHONPATH:+:\$PYTHONPATH}" \\
LD_LIBRARY_PATH="$pv_libdir\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}" \\
  exec "$PV_PY_DIR/usr/bin/pvpython" "\$@"
EOF
chmod +x "$DEPS_DIR/bin/pvpython.tmp"
if cmp -s "$DEPS_DIR/bin/pvpython.tmp" "$DEPS_DIR/bin/pvpython"; then
  rm "$DEPS_DIR/bin/pvpython.tmp"
else
  mv "$DEPS_DIR/bin/pvpython.tmp" "$DEPS_DIR/bin/pvpython"
fi

# --- ParaView's CMake package, private copy ---------------------------------------------------
pv_cmake="$PV_CMAKE_DIR/$(basename "$pv_cmake_src")"
# The stamp names what the copy was made from and how (bump the last word when the rules change).
pv_cmake_stamp="$pv_version $PV_PY_DIR rules-2"
if [ "$(stamp "$PV_CMAKE_DIR")" != "$pv_cmake_stamp" ]; then
  log "writing a private copy of ParaView's CMake package into $pv_cmake"
  rm -rf "$PV_CMAKE_DIR"
  mkdir -p "$PV_CMAKE_DIR"
  cp -r "$pv_cmake_src" "$pv_cmake"
  # Each file computes the install prefix from its own location: compute it from the original's,
  # then send the files of python3-paraview (pvpython, the Python modules, the wrapping
  # hierarchies) to the unpacked copy.
  pv_py_rules=()
  for prefix in _IMPORT_PREFIX _vtk_module_import_prefix; do
    for path in bin/pvpython lib/python3/dist-packages/ "${pv_libdir#/usr/}/vtk/hierarchy/"; do
      pv_py_rules+=(-e "s|\${$prefix}/$path|$PV_PY_DIR/usr/$path|g")
    done
  done
  while IFS= read -r -d '' f; do
    orig_dir="$(dirname "$pv_cmake_src${f#"$pv_cmake"}")"
    sed -i \
      -e "s|get_filename_component(_IMPORT_PREFIX \"\${CMAKE_CURRENT_LIST_FILE}\" PATH)|set(_IMPORT_PREFIX \"$orig_dir\")|" \
      -e "s|set(_vtk_module_import_prefix \"\${CMAKE_CURRENT_LIST_DIR}\")|set(_vtk_module_import_prefix \"$orig_dir\")|" \
      -e "s|get_filename_component(PACKAGE_PREFIX_DIR \"\${CMAKE_CURRENT_LIST_DIR}/|get_filename_component(PACKAGE_PREFIX_DIR \"$orig_dir/|" \
      "${pv_py_rules[@]}" "$f"
  done < <(find "$pv_cmake" -name '*.cmake' -print0)
  # Debian 13 names the extension modules X.cpython-313-x86_64-linux-gnu.so, its CMake targets
  # still X.so: point those at the files that exist.
  renames="$PV_CMAKE_DIR/renames.sed"
  : > "$renames"
  while IFS= read -r module; do
    for renamed in "${module%.so}".cpython-*.so; do
      if [ ! -e "$module" ] && [ -e "$renamed" ]; then
        printf 's|%s"|%s"|g\n' "$module" "$renamed" >> "$renames"
      fi
    done
  done < <(grep -rhoE "$pv_site/[^\" ]*\.so" "$pv_cmake" | sort -u)
  if [ -s "$renames" ]; then
    find "$pv_cmake" -name '*.cmake' -exec sed -i -f "$renames" {} +
  fi
  if grep -rlq -e '_IMPORT_PREFIX "${CMAKE_CURRENT_LIST_FILE}"' \
       -e '_vtk_module_import_prefix "${CMAKE_CURRENT_LIST_DIR}"' "$pv_cmake"; then
    die "ParaView's CMake package computes its prefix in a way this script does not know"
  fi
  printf '%s\n' "$pv_cmake_stamp" > "$PV_CMAKE_DIR/.version"
fi

case "$PROFILE" in paraview|docs) exit 0 ;; esac

# --- The converters of the capture format tests -------------------------------------------------
TOOLS_DIR="$DEPS_DIR/capture-tools"
if [ "$(stamp "$TOOLS_DIR")" != "${CAPTURE_TOOLS[*]}" ]; then
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
