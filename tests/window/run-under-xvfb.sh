#!/bin/sh
# Runs a test program under a virtual X server (xvfb-run -a), so that VTK's
# default X11 window (vtkXOpenGLRenderWindow, Mesa GLX) can be tested on a
# machine without a display. Without xvfb-run: on the current display when
# there is one, else exit 77 (CTest SKIP_RETURN_CODE).
if command -v xvfb-run >/dev/null 2>&1; then
  # xvfb-run -a can race with another xvfb-run -a started at the same
  # moment (both pick the same free display): retry when the server itself
  # failed to start (its errors go to the -e file), never on a test failure.
  errors=$(mktemp)
  for attempt in 1 2 3; do
    xvfb-run -a -e "$errors" -s "-screen 0 1024x768x24" "$@"
    rc=$?
    if [ "$rc" -ne 0 ] && grep -q "Server is already active\|Fatal server error" "$errors"; then
      echo "run-under-xvfb: Xvfb did not start (attempt $attempt), retrying" >&2
      : >"$errors"
      sleep 1
      continue
    fi
    break
  done
  rm -f "$errors"
  exit "$rc"
fi
if [ -n "${DISPLAY:-}" ]; then
  exec "$@"
fi
echo "SKIP: xvfb-run not found (apt-get install xvfb xauth) and no DISPLAY"
exit 77
