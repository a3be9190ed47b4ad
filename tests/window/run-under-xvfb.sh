#!/bin/sh
# Runs a test program under a virtual X server (xvfb-run -a), so that VTK's
# default X11 window (vtkXOpenGLRenderWindow, Mesa GLX) can be tested on a
# machine without a display. Without xvfb-run: on the current display when
# there is one, else exit 77 (CTest SKIP_RETURN_CODE).
if command -v xvfb-run >/dev/null 2>&1; then
  exec xvfb-run -a -s "-screen 0 1024x768x24" "$@"
fi
if [ -n "${DISPLAY:-}" ]; then
  exec "$@"
fi
echo "SKIP: xvfb-run not found (apt-get install xvfb xauth) and no DISPLAY"
exit 77
