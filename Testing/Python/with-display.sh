#!/bin/sh
# with-display.sh XVFB_RUN COMMAND [ARG...]
# Runs COMMAND directly when an X display is set, else under XVFB_RUN (a private Xvfb server).
xvfb_run=$1
shift
if [ -n "${DISPLAY:-}" ]; then
  exec "$@"
fi
case "$xvfb_run" in
  ""|*-NOTFOUND)
    echo "with-display.sh: DISPLAY is unset and xvfb-run was not found" >&2
    exit 1 ;;
esac
exec "$xvfb_run" -a -s "-screen 0 1280x1024x24" "$@"
