#!/usr/bin/env bash
# Installs the dependencies (if missing), configures and builds vtkrt in ./build.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
BUILD_DIR=${VTKRT_BUILD_DIR:-build}
JOBS=${VTKRT_JOBS:-$(nproc)}
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVTKRT_WRAP_PYTHON=ON ${VTKRT_CMAKE_ARGS:-}
cmake --build "$BUILD_DIR" -j "$JOBS"
