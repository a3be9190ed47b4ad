#!/usr/bin/env bash
# README command 2: install, build, then run the whole test suite through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
# VTKRT_ONLY_PARAVIEW=1 skips the main suite (to check the ParaView stage alone).
if [ "${VTKRT_ONLY_PARAVIEW:-0}" != 1 ]; then
bash scripts/build.sh
BUILD_DIR=${VTKRT_BUILD_DIR:-build}
(cd "$BUILD_DIR" && ctest --output-on-failure -j "${VTKRT_JOBS:-$(nproc)}" "$@")
# ThreadSanitizer over the locator's thread tests (a fresh locator queried
# from several threads among them), in its own build folder.
# VTKRT_SKIP_TSAN=1 skips it.
if [ "${VTKRT_SKIP_TSAN:-0}" != 1 ]; then
  bash scripts/sanitize.sh tsan
fi
fi
# ParaView stage, after the main suite passed: swaps in Debian's ParaView,
# builds and tests the plugin, swaps the system VTK back (also on failure).
# VTKRT_SKIP_PARAVIEW=1 skips it.
if [ "${VTKRT_SKIP_PARAVIEW:-0}" != 1 ]; then
  bash scripts/test-paraview.sh
fi
