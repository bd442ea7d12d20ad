#!/usr/bin/env bash
# The GPU check: the OpenGL backends' figures and image tests on a machine with a GPU that has
# none of Debian's VTK, OpenVDB, X server or Mesa and no package registry (the device machine of
# docs/gpu-check.md), from one archive packed here.
#
#   scripts/gpu-check.sh pack VTK_BUILD        here (./splat gpu-check pack sets up and builds
#                                              first): build/gpu-check/splat-gpu-check.tar.xz
#   scripts/gpu-check.sh run [ARCHIVE] [--quick]
#                                              there: unpacks to /tmp, starts the X server, runs
#                                              the checks, writes to $OUT (default
#                                              output/gpu-check)
#   scripts/gpu-check.sh verify                here: `run --quick` in a minimal Debian 12 root
#                                              that has no VTK, OpenVDB, X or Mesa package
#   scripts/gpu-check.sh report DIR...         here: docs/gpu-performance.md and docs/gpu/ from
#                                              the files a run returned (each CSV from the last
#                                              DIR that has it)
#
# The archive holds splat_bench, splat_render, the CPU-against-OpenGL tests, their shared-library
# closure as ldd finds it (VTK, OpenVDB, TBB, libglvnd, ...; not the C library, which every Linux
# has, nor a GL vendor library of the GPU's), Xvfb with xkbcomp and its keyboard data, and a
# Mesa for the X server's GLX extension, built here with softpipe only: Debian's Mesa needs
# LLVM, which alone would take most of the 56 MiB the archive may have (a device call carries
# 64 MiB with the working tree). On the GPU the programs draw through the driver's own
# libGLX_nvidia (__GLX_VENDOR_LIBRARY_NAME=nvidia); where there is none (the verification) they
# draw through the archive's Mesa.
#
# run: the checks run in order of importance within SPLAT_GPU_CHECK_SECONDS (default 480), each
# cut off when the time is spent: the OpenGL renderer and GPU (summary.txt), the image tests
# (TestSurfaceSplatBackends, TestVolumeSplatBackends, TestVolumeSplatSphericalHarmonics), the
# bench's OpenGL surface rows (sphere 1 M and 5 M, the bunny, at 1024^2, vtkPointGaussianMapper
# in the same run) and volume rows (the MRI, gaussians, 3dgs, vdb at 1024^2, the ray casters in
# the same run), and the GPU time of each render pass of a later frame of the sphere, the MRI, the
# capture and the fog (splat_bench --gpu-timings, into checks.log). Files in $OUT: summary.txt, checks.log, bench-surface.csv, bench-volume.csv,
# gpu-memory.csv (nvidia-smi's used memory every second) and images.tar (the tests' images, and
# the bench's last frames where they fit). --quick: the bench's smoke sizes. It exits non-zero
# when a check failed. SPLAT_GPU_CHECKS (a comma-separated list of the checks' names, as in
# summary.txt) runs only those.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WORK="${SPLAT_BUILD_ROOT:-$ROOT/build}/gpu-check"
ARCHIVE="$WORK/splat-gpu-check.tar.xz"
MAX_ARCHIVE_BYTES=$((56 * 1024 * 1024))
PROGRAMS=(splat_bench splat_render TestSurfaceSplatBackends TestVolumeSplatBackends
  TestVolumeSplatSphericalHarmonics)
# The C library's own files: every machine has them, and they must match its ld.so.
GLIBC='^(ld-linux-x86-64|libc|libm|libdl|libpthread|librt|libresolv|libutil|libanl)\.so'

say() { printf 'gpu-check: %s\n' "$*" >&2; }
die() { printf 'gpu-check: error: %s\n' "$*" >&2; exit 1; }

# --- pack -------------------------------------------------------------------------------------

# Builds Debian 12's Mesa source (fetched with a private apt source list, the host's left
# alone) with the software rasterizer softpipe and no LLVM into $WORK/mesa/install, once.
build_mesa() {
  local dir="$WORK/mesa"
  local dri="$dir/install/lib/dri/swrast_dri.so"
  [ -f "$dri" ] && return 0
  say "building Mesa (softpipe, no LLVM) in $dir; about 15 minutes on 2 cores"
  rm -rf "$dir"
  mkdir -p "$dir/lists/partial"
  printf 'deb-src %s bookworm main\n' "${SPLAT_DEBIAN_MIRROR:-http://deb.debian.org/debian}" \
    >"$dir/sources.list"
  local apt=(apt-get -q -o "Dir::Etc::SourceList=$dir/sources.list"
    -o Dir::Etc::SourceParts=/dev/null -o "Dir::State::Lists=$dir/lists")
  "${apt[@]}" update >"$dir/apt.log" 2>&1 || { cat "$dir/apt.log" >&2; die "apt-get update"; }
  (cd "$dir" && "${apt[@]}" source --download-only mesa >>"$dir/apt.log" 2>&1) \
    || { cat "$dir/apt.log" >&2; die "apt-get source mesa"; }
  tar -C "$dir" -xzf "$dir"/mesa_*.orig.tar.gz
  # Debian's python3 (the one with mako), not a python3 of the caller's PATH.
  PATH="/usr/bin:/bin" meson setup "$dir/build" "$dir"/mesa-*/ --buildtype=release \
    --prefix="$dir/install" --libdir=lib -Dgallium-drivers=swrast -Dvulkan-drivers= \
    -Dllvm=disabled -Dglx=dri -Degl=disabled -Dgbm=disabled -Dgles1=disabled -Dgles2=disabled \
    -Dplatforms=x11 -Dshared-glapi=enabled -Dglvnd=true -Dzstd=disabled -Dvalgrind=disabled \
    -Dlibunwind=disabled -Dlmsensors=disabled -Dgallium-vdpau=disabled -Dgallium-va=disabled \
    -Dgallium-xa=disabled -Dgallium-omx=disabled -Dgallium-nine=false \
    -Dgallium-opencl=disabled -Dosmesa=false -Dbuild-tests=false >"$dir/meson.log" 2>&1 \
    || { tail -n 30 "$dir/meson.log" >&2; die "Mesa's meson setup failed"; }
  PATH="/usr/bin:/bin" ninja -C "$dir/build" -j "${SPLAT_JOBS:-2}" install >"$dir/ninja.log" 2>&1 \
    || { tail -n 30 "$dir/ninja.log" >&2; die "Mesa's build failed"; }
  [ -f "$dri" ] || die "Mesa's build made no $dri"
}

# closure FILE...: the shared libraries FILEs load, as "NAME PATH" lines, the C library's left
# out; fails on a library ldd cannot find.
closure() {
  local file libraries
  for file in "$@"; do
    libraries="$(ldd "$file")"
    if grep -q 'not found' <<<"$libraries"; then
      grep 'not found' <<<"$libraries" >&2
      die "$file needs libraries that are not found"
    fi
    awk '$2 == "=>" && $3 ~ /^\// { print $1, $3 }' <<<"$libraries"
  done | sort -u | grep -Ev "$GLIBC" || true
}

cmd_pack() {
  local build="${1:?usage: scripts/gpu-check.sh pack VTK_BUILD}"
  build="$(cd "$build" && pwd)"
  build_mesa
  local mesa="$WORK/mesa/install/lib"
  local stage="$WORK/stage/splat-gpu"
  rm -rf "$WORK/stage"
  mkdir -p "$stage/bin" "$stage/lib/dri" "$stage/share/X11" "$stage/data" "$stage/images"
  local name
  for name in "${PROGRAMS[@]}"; do
    [ -x "$build/bin/$name" ] || die "$build/bin/$name was not built"
    cp "$build/bin/$name" "$stage/bin/"
  done
  cp "$(command -v Xvfb)" "$(command -v xkbcomp)" "$stage/bin/"
  cp -rL /usr/share/X11/xkb "$stage/share/X11/"
  cp "$mesa/dri/swrast_dri.so" "$stage/lib/dri/"
  cp -L "$mesa/libGLX_mesa.so.0" "$mesa/libglapi.so.0" "$stage/lib/"
  local lib path
  while read -r lib path; do
    [ -e "$stage/lib/$lib" ] || cp -L "$path" "$stage/lib/$lib"
  done < <(LD_LIBRARY_PATH="$mesa:$build/lib" closure "$stage"/bin/* "$stage/lib/dri/swrast_dri.so" \
    "$stage/lib/libGLX_mesa.so.0")
  # The bench's and tests' data where this machine has it: the bunny and the MRI head.
  local data="${SPLAT_DATA_DIR:-$ROOT/../shared/data}"
  [ -f "$data/bunny.ply" ] && cp "$data/bunny.ply" "$stage/data/"
  local mri="${SPLAT_MRI_FILE:-/usr/share/mricron/templates/ch2.nii.gz}"
  [ -f "$mri" ] && cp "$mri" "$stage/data/ch2.nii.gz"
  {
    echo "commit $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
    echo "packed $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(. /etc/os-release && echo "$PRETTY_NAME")"
    (cd "$stage" && find . -type f | sort)
  } >"$stage/MANIFEST"
  say "compressing $(du -sh "$stage" | cut -f1) into $ARCHIVE"
  tar -C "$WORK/stage" -cf - splat-gpu \
    | xz -T "${SPLAT_JOBS:-2}" --x86 --lzma2=preset=9e >"$ARCHIVE.part"
  mv "$ARCHIVE.part" "$ARCHIVE"
  local bytes
  bytes="$(stat -c %s "$ARCHIVE")"
  say "$ARCHIVE: $((bytes / 1024 / 1024)) MiB, $(find "$stage/lib" -maxdepth 1 -type f | wc -l) libraries"
  [ "$bytes" -le "$MAX_ARCHIVE_BYTES" ] \
    || die "the archive is over $((MAX_ARCHIVE_BYTES / 1024 / 1024)) MiB: a device call cannot carry it"
}

# --- run --------------------------------------------------------------------------------------

cmd_run() {
  local archive="$ARCHIVE" quick=0 arg
  for arg in "$@"; do
    case "$arg" in
      --quick) quick=1 ;;
      *) archive="$arg" ;;
    esac
  done
  [ -f "$archive" ] || die "no archive $archive: run scripts/gpu-check.sh pack first"
  local out="${OUT:-$ROOT/output/gpu-check}"
  mkdir -p "$out"
  local deadline=$((SECONDS + ${SPLAT_GPU_CHECK_SECONDS:-480}))
  local summary="$out/summary.txt" log="$out/checks.log"
  : >"$summary"
  : >"$log"
  local R=/tmp/splat-gpu
  rm -rf "$R"
  # xz, or Python's lzma where xz is not installed.
  if command -v xz >/dev/null 2>&1; then
    xz -dc "$archive" | tar -C /tmp -xf -
  else
    python3 -c 'import lzma, shutil, sys; shutil.copyfileobj(lzma.open(sys.argv[1]), sys.stdout.buffer)' \
      "$archive" | tar -C /tmp -xf -
  fi
  head -n 2 "$R/MANIFEST" >>"$summary"

  # Only the archive's programs see its libraries (the machine's own tools keep theirs): the X
  # server with the archive's Mesa, the programs with the GPU's GLX vendor library too.
  local x_env=(env "LD_LIBRARY_PATH=$R/lib" "LIBGL_DRIVERS_PATH=$R/lib/dri")
  local run_env=("${x_env[@]}")
  # The GPU's GLX vendor library, where the driver put it.
  local vendor="" candidate
  for candidate in /usr/local/nvidia/lib64 /usr/local/nvidia/lib /usr/lib/x86_64-linux-gnu; do
    if [ -e "$candidate/libGLX_nvidia.so.0" ]; then
      vendor="$candidate/libGLX_nvidia.so.0"
      break
    fi
  done
  if [ -n "$vendor" ]; then
    run_env=(env "LD_LIBRARY_PATH=$R/lib:$(dirname "$vendor")" "LIBGL_DRIVERS_PATH=$R/lib/dri"
      __GLX_VENDOR_LIBRARY_NAME=nvidia)
    echo "GLX vendor library: $vendor" >>"$summary"
  else
    echo "GLX vendor library: none of the GPU's; the archive's Mesa (softpipe)" >>"$summary"
  fi
  # Xvfb runs the keymap compiler from the path it was built with.
  if [ ! -x /usr/bin/xkbcomp ] && ! ln -sf "$R/bin/xkbcomp" /usr/bin/xkbcomp; then
    echo "cannot link /usr/bin/xkbcomp (not root?): the X server may not start" >>"$summary"
  fi
  local display=77
  # A display is taken when its socket or lock file is there, or its abstract socket (shared
  # with other roots on the machine).
  while [ -e "/tmp/.X11-unix/X$display" ] || [ -e "/tmp/.X$display-lock" ] \
    || grep -q "@/tmp/.X11-unix/X$display\$" /proc/net/unix 2>/dev/null; do
    display=$((display + 1))
  done
  "${x_env[@]}" "$R/bin/Xvfb" ":$display" -screen 0 1280x1024x24 -nolisten tcp -noreset \
    -xkbdir "$R/share/X11/xkb" >"$out/xvfb.log" 2>&1 &
  XVFB_PID=$!
  MEMORY_PID=""
  trap 'kill "$XVFB_PID" ${MEMORY_PID:+"$MEMORY_PID"} 2>/dev/null || true' EXIT
  for _ in $(seq 50); do
    [ -e "/tmp/.X11-unix/X$display" ] && break
    sleep 0.2
  done
  if [ ! -e "/tmp/.X11-unix/X$display" ]; then
    echo "the X server did not start:" >>"$summary"
    tail -n 20 "$out/xvfb.log" >>"$summary"
    cat "$summary" >&2
    return 1
  fi
  export DISPLAY=":$display"
  if command -v nvidia-smi >/dev/null 2>&1; then
    nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader >>"$summary" || true
    nvidia-smi --query-gpu=timestamp,memory.used --format=csv -l 1 >"$out/gpu-memory.csv" 2>&1 &
    MEMORY_PID=$!
  fi

  local failed=()
  # check NAME SECONDS COMMAND...: runs COMMAND for at most SECONDS (less when the time left is
  # less), its output appended to checks.log, its outcome to summary.txt.
  check() {
    local name="$1" limit="$2"
    shift 2
    if [ -n "${SPLAT_GPU_CHECKS:-}" ] && [[ ",$SPLAT_GPU_CHECKS," != *",$name,"* ]]; then
      return 0
    fi
    local left=$((deadline - SECONDS))
    [ "$left" -lt "$limit" ] && limit="$left"
    if [ "$limit" -le 5 ]; then
      echo "$name: not run (no time left)" >>"$summary"
      failed+=("$name")
      return 0
    fi
    printf '\n=== %s: %s\n' "$name" "$*" >>"$log"
    local start=$SECONDS status=0
    # Line-buffered, so that a program cut off leaves what it printed.
    timeout --kill-after=10 "$limit" stdbuf -oL -eL "${run_env[@]}" "$@" >>"$log" 2>&1 \
      || status=$?
    local outcome="passed"
    [ "$status" -eq 0 ] || { outcome="FAILED (exit $status)"; failed+=("$name"); }
    [ "$status" -eq 124 ] && outcome="CUT OFF after ${limit} s"
    echo "$name: $outcome in $((SECONDS - start)) s" >>"$summary"
  }

  export SPLAT_DATA_DIR="$R/data" SPLAT_MRI_FILE="$R/data/ch2.nii.gz"
  local size=256x256
  [ "$quick" = 1 ] && size=64x64
  check renderer 60 "$R/bin/splat_render" "$R/data/bunny.ply" --backend opengl --size "$size" \
    --frames 1 --output "$R/images/renderer-bunny.png"
  grep -h "OpenGL renderer" "$log" | tail -n 1 >>"$summary" || true
  # Under softpipe (--quick, the verification) the tests are slow: there they only have to start.
  local test test_limit=150
  [ "$quick" = 1 ] && test_limit=30
  for test in TestSurfaceSplatBackends TestVolumeSplatBackends TestVolumeSplatSphericalHarmonics; do
    check "$test" "$test_limit" "$R/bin/$test" -D "$R/data" -T "$R/images"
  done
  local surface=(--scenes "sphere,bunny" --backends opengl --mappers "splat,pointgaussian")
  local volume=(--scenes "mri,gaussians,3dgs,vdb" --backends opengl
    --mappers "splat,gpuraycast,fixedpoint")
  if [ "$quick" = 1 ]; then
    # Few kernels: softpipe's texture buffers hold 65536 texels (a GPU's, 2^27).
    surface+=(--quick --points 5000)
    volume+=(--quick --orderings blended --kernels 2000 --voxels 4000 --mri-shrink 8)
  else
    surface+=(--points "1000000,5000000" --sizes 1024 --budget 4)
    volume+=(--sizes 1024 --budget 4)
  fi
  # The CSVs are written beside the bench's files (the vdb scene's grid) and copied to $OUT.
  mkdir -p "$R/images/bench" "$R/bench"
  check bench-surface 200 "$R/bin/splat_bench" "${surface[@]}" --output "$R/bench/bench-surface.csv" \
    --image-dir "$R/images/bench"
  check bench-volume 300 "$R/bin/splat_bench" "${volume[@]}" --output "$R/bench/bench-volume.csv" \
    --image-dir "$R/images/bench"
  cp "$R"/bench/*.csv "$out/" 2>/dev/null || true
  # The GPU time of each pass of a later frame (the render timer log), into checks.log; at two
  # sizes, since a pass whose time does not follow the pixels is bound by its vertex work.
  local timings=(--scenes "sphere,mri,3dgs,vdb" --points 1000000 --sizes 256,1024 --backends opengl
    --mappers splat --orderings "blended,depth-sorted" --frames 3 --budget 2)
  [ "$quick" = 1 ] && timings=(--scenes sphere --quick --points 5000 --backends opengl
    --mappers splat)
  mkdir -p "$R/timings"
  check timings 150 "$R/bin/splat_bench" "${timings[@]}" --gpu-timings \
    --output "$R/timings/bench.csv"

  cat "$out/xvfb.log" >>"$log"
  rm -f "$out/xvfb.log"
  # The tests' images, and the bench's last frames where they fit a returned file (16 MiB).
  tar -C "$R/images" --exclude=./bench -cf "$out/images.tar" .
  tar -C "$R/images" -rf "$out/images.tar" bench
  [ "$(stat -c %s "$out/images.tar")" -le $((15 * 1024 * 1024)) ] \
    || tar -C "$R/images" --exclude=./bench -cf "$out/images.tar" .
  if [ "${#failed[@]}" -gt 0 ]; then
    echo "failed: ${failed[*]}" >>"$summary"
    cat "$summary" >&2
    return 1
  fi
  echo "all checks passed" >>"$summary"
  cat "$summary" >&2
}

# --- verify -----------------------------------------------------------------------------------

# The packages a clean root must not have: if it had them, the archive's closure could be
# incomplete and still run.
ABSENT=(libvtk9.1 libopenvdb10.0 libtbb12 xvfb x11-xkb-utils libgl1-mesa-dri libglx-mesa0
  libglvnd0 libx11-6)

cmd_verify() {
  [ -f "$ARCHIVE" ] || die "no archive $ARCHIVE: run ./splat gpu-check pack first"
  local out="$ROOT/output/gpu-check-verify"
  rm -rf "$out"
  mkdir -p "$out"
  say "checking that the Debian 12 root has none of: ${ABSENT[*]}"
  bash "$ROOT/scripts/debian-root.sh" 12 /bin/bash -c \
    'for p in "$@"; do
       if [ "$(dpkg-query -W --showformat="\${db:Status-Status}" "$p" 2>/dev/null)" = installed ]
       then
         echo "the root has $p" >&2; exit 1
       fi
     done' absent "${ABSENT[@]}"
  say "running the checks (--quick) in it, on the archive's Mesa"
  local status=0
  bash "$ROOT/scripts/debian-root.sh" 12 /usr/bin/env OUT="$out" \
    SPLAT_GPU_CHECK_SECONDS="${SPLAT_GPU_CHECK_SECONDS:-900}" \
    bash "$ROOT/scripts/gpu-check.sh" run "$ARCHIVE" --quick || status=$?
  # What must hold there: every program loaded and ran (an incomplete closure stops them before
  # main), and the bench wrote OpenGL rows of every scene with the columns of this machine's.
  local header
  header="$(head -n 1 "$out/bench-surface.csv" 2>/dev/null || true)"
  [ -n "$header" ] || die "no bench-surface.csv: see $out/checks.log"
  grep -q "error while loading shared libraries" "$out/checks.log" \
    && die "a library is missing from the archive: see $out/checks.log"
  local scene
  for scene in sphere bunny; do
    grep -q "^$scene,vtkSurfaceSplatMapper,OpenGL," "$out/bench-surface.csv" \
      || die "bench-surface.csv has no OpenGL row of $scene"
  done
  for scene in mri gaussians 3dgs vdb; do
    grep -q "^$scene,vtkVolumeSplatMapper,OpenGL," "$out/bench-volume.csv" \
      || die "bench-volume.csv has no OpenGL row of $scene"
  done
  [ "$(head -n 1 "$out/bench-volume.csv")" = "$header" ] || die "the CSVs' columns differ"
  say "verified: the archive runs in a root without VTK, OpenVDB, X or Mesa ($out)"
  [ "$status" -eq 0 ] || say "some checks failed there (softpipe, not a GPU): see $out/summary.txt"
}

# --- report -----------------------------------------------------------------------------------

# The figures of returned runs into the docs, never copied by hand: the CSVs and each one's
# summary.txt (GPU, driver, renderer, commit) into docs/gpu/, and their tables.
cmd_report() {
  [ "$#" -gt 0 ] || die "report: name the folders a run's files came back to"
  local docs="$ROOT/docs" name dir source
  mkdir -p "$docs/gpu"
  local page="$docs/gpu-performance.md"
  {
    cat <<'EOF'
# Performance on a GPU

The OpenGL backends on a data-center GPU, from [the GPU check](gpu-check.md): milliseconds per
frame at 1024x1024 and the peer's time as a ratio (`peer_ratio` above 1: faster than the peer,
measured in the same run: `vtkPointGaussianMapper` for surfaces, `vtkFixedPointVolumeRayCastMapper`
for volumes). The CPU's figures: [performance.md](performance.md). Generated by
`./splat gpu-check report` from the files the run returned, kept in [gpu/](gpu/).
EOF
    for name in bench-surface bench-volume; do
      source=""
      for dir in "$@"; do
        if [ -f "$dir/$name.csv" ]; then source="$dir"; fi
      done
      [ -n "$source" ] || continue
      cp "$source/$name.csv" "$docs/gpu/$name.csv"
      cp "$source/summary.txt" "$docs/gpu/$name-summary.txt"
      printf '\n## %s\n\n' "${name#bench-}"
      printf 'Commit %s on %s; %s.\n\n' \
        "$(sed -n 's/^commit //p' "$source/summary.txt")" \
        "$(grep -m 1 'MiB$' "$source/summary.txt" || echo 'an unnamed GPU')" \
        "$(sed -n 's/^ *backend: *//p' "$source/summary.txt" | head -n 1)"
      awk -F, -f "$ROOT/scripts/bench-table.awk" "$source/$name.csv"
    done
  } >"$page"
  say "wrote $page"
}

case "${1:-}" in
  pack) shift; cmd_pack "$@" ;;
  report) shift; cmd_report "$@" ;;
  run) shift; cmd_run "$@" ;;
  verify) shift; cmd_verify "$@" ;;
  *) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -e '/^set -euo/d' -e 's/^# \{0,1\}//' >&2
     exit 2 ;;
esac
