#!/usr/bin/env bash
# README command 1: install, build, then render the built-in demo scene headless
# to vtkrt-demo.png, ray traced when this build has the pass (else rasterized).
# Extra arguments go to vtkrt-render (a later --mode wins).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
BUILD_DIR=${VTKRT_BUILD_DIR:-build}
APP="$BUILD_DIR/bin/vtkrt-render"
MODE=raster
if "$APP" --help | grep -q "raytrace mode available"; then
  MODE=raytrace
fi
"$APP" --demo --size 1024x768 --mode "$MODE" --output vtkrt-demo.png "$@"
