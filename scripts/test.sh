#!/usr/bin/env bash
# README command 2: install, build, then run the whole test suite through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
BUILD_DIR=${VTKRT_BUILD_DIR:-build}
cd "$BUILD_DIR"
ctest --output-on-failure -j "${VTKRT_JOBS:-$(nproc)}" "$@"
