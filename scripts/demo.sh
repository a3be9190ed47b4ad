#!/usr/bin/env bash
# README command 1: install, build, then render the built-in demo scene headless.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
BUILD_DIR=${VTKRT_BUILD_DIR:-build}
"$BUILD_DIR/bin/vtkrt-render" --demo --size 1024x768 --output vtkrt-demo.png "$@"
