#!/bin/sh
# Runs a ParaView test command with an X server: the current one when DISPLAY
# is set (CI runs the whole ParaView ctest under one xvfb-run), else a
# private Xvfb (-noreset: an X server resets when its last client leaves,
# and a test connecting during the reset fails). Debian's ParaView renders
# through GLX only.
if [ -n "${DISPLAY:-}" ]; then
  exec "$@"
fi
exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$@"
