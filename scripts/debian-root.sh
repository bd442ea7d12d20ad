#!/usr/bin/env bash
# Runs a command in a minimal Debian root: Debian 13 (trixie) for the second test leg (VTK 9.3,
# ParaView 5.13), Debian 12 (bookworm) for the GPU check's clean-root verification
# (scripts/gpu-check.sh verify).
#
#   scripts/debian-root.sh 12|13 COMMAND [ARG...]
#   SPLAT_DEBIAN13_ROOT=DIR   the Debian 13 root (default: build/deps/debian13-root in the
#                             repository; the Debian 12 root is build/deps/debian12-root)
#
# Makes the root once with debootstrap --variant=minbase (from the package archive the host
# uses; about 35 s) and reuses it afterwards. COMMAND runs there as root with /proc, /sys and
# /dev mounted and the repository (and ../shared beside it, where present) bind-mounted at their
# own paths, so that build trees and test data have the same names inside and out; everything is
# unmounted when it ends. Packages inside the root are installed by the project's own set-up,
# run there: the host's apt and dpkg are not touched.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DEPS_DIR="${SPLAT_DEPS_DIR:-$ROOT/build/deps}"
MIRROR="${SPLAT_DEBIAN_MIRROR:-http://deb.debian.org/debian}"

log() { printf 'debian-root: %s\n' "$*" >&2; }
die() { printf 'debian-root: error: %s\n' "$*" >&2; exit 1; }

VERSION="${1:-}"
case "$VERSION" in
  # xz-utils: the GPU check's archive is .xz (the device machine's python3 can also unpack it)
  12) SUITE=bookworm; TARGET="$DEPS_DIR/debian12-root"; INCLUDE=(--include=xz-utils) ;;
  13) SUITE=trixie; TARGET="${SPLAT_DEBIAN13_ROOT:-$DEPS_DIR/debian13-root}"; INCLUDE=() ;;
  *) die "usage: scripts/debian-root.sh 12|13 COMMAND [ARG...]" ;;
esac
shift
[ "$#" -gt 0 ] || die "usage: scripts/debian-root.sh 12|13 COMMAND [ARG...]"
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || die "chroot needs root, and sudo is not available"
  exec sudo --preserve-env=SPLAT_DEPS_DIR,SPLAT_DEBIAN13_ROOT,SPLAT_DEBIAN_MIRROR \
    bash "${BASH_SOURCE[0]}" "$VERSION" "$@"
fi

if [ ! -f "$TARGET/.splat-complete" ]; then
  command -v debootstrap >/dev/null 2>&1 || die "debootstrap is missing: run scripts/setup.sh test"
  log "making a Debian $VERSION root in $TARGET"
  # Never remove a root with something still mounted in it (the repository, say).
  if grep -q " $TARGET/" /proc/self/mounts; then
    die "$TARGET has mounts left inside (see /proc/self/mounts): unmount them first"
  fi
  rm -rf "$TARGET"
  mkdir -p "$TARGET" "$DEPS_DIR"
  debootstrap --variant=minbase "${INCLUDE[@]}" "$SUITE" "$TARGET" "$MIRROR" \
    >"$DEPS_DIR/debian$VERSION-debootstrap.log" 2>&1 \
    || { tail -n 20 "$DEPS_DIR/debian$VERSION-debootstrap.log" >&2; die "debootstrap failed"; }
  touch "$TARGET/.splat-complete"
fi
# Name resolution for apt inside.
cp /etc/resolv.conf "$TARGET/etc/resolv.conf"

mounted=()
cleanup() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount -R "${mounted[i]}" 2>/dev/null || umount -lR "${mounted[i]}" || true
  done
}
trap cleanup EXIT
# bind OPTION SOURCE: mounts SOURCE at the same path inside the root (OPTION --rbind for the
# system trees with their submounts, --bind for the repository, which holds the root itself).
bind() {
  mkdir -p "$TARGET$2"
  mount "$1" "$2" "$TARGET$2"
  mount --make-rslave "$TARGET$2"
  mounted+=("$TARGET$2")
}
mount -t proc proc "$TARGET/proc"
mounted+=("$TARGET/proc")
bind --rbind /sys
bind --rbind /dev
bind --bind "$ROOT"
shared="$(cd "$ROOT/.." && pwd)/shared"
if [ -d "$shared" ]; then
  bind --bind "$shared"
fi

chroot "$TARGET" /usr/bin/env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 \
  "$@"
