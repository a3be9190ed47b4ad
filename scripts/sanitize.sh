#!/usr/bin/env bash
# Builds vtkrt's tests with sanitizers in their own build folder and runs a
# subset of them: `scripts/sanitize.sh asan` (AddressSanitizer and
# UndefinedBehaviorSanitizer over the core and locator labels) or
# `scripts/sanitize.sh tsan` (ThreadSanitizer over the locator's thread tests
# and the pass's background builds).
# VTKRT_SANITIZE_TESTS overrides the ctest selection (ctest arguments);
# VTKRT_JOBS the parallelism (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-asan}
jobs=${VTKRT_JOBS:-2}
supp="$PWD/tests/sanitizers"
case "$mode" in
  asan)
    sanitize="address,undefined"
    targets=(TestBVHCellLocator TestCoreKernels TestCoreBVHQueries TestCoreWatertight TestCoreExtremes
      TestCoreBuild TestCoreTwoLevel TestCoreConservativeFloat TestCoreWideBVH TestCoreGpuTwins
      TestCoreSurfaceTriangulation TestCoreGpuTranslucency TestCoreTubeTwins TestCoreGpuWalkStarts)
    default_tests=(-L 'core|locator')
    # Leak checking stays on; the suppressions may list third-party
    # libraries only.
    mesa_dri=${VTKRT_MESA_DRI:-/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so}
    export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:check_initialization_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
    export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
    export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
    ;;
  tsan)
    sanitize="thread"
    targets=(TestBVHCellLocator TestRayTracePassBehavior TestRayTraceRefinement)
    default_tests=(-R '^(locator\.(Threads|FreshLocatorThreads)|pass\.(BackgroundBuild|Queue))$')
    # TBB is not instrumented, so TSan cannot see its task hand-offs and
    # reports the builder's parallel loops as races; VTK's STDThread pool
    # synchronises through pthreads, which TSan sees.
    export VTK_SMP_BACKEND_IN_USE=${VTK_SMP_BACKEND_IN_USE:-STDThread}
    export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$supp/tsan.supp${TSAN_OPTIONS:+:$TSAN_OPTIONS}"
    ;;
  *) echo "usage: $0 [asan|tsan]" >&2; exit 2 ;;
esac
# The sanitizer's runtime must start on this kernel and toolchain (TSan
# refuses some address-space layouts); if it cannot, say so and stop.
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
echo 'int main() { return 0; }' >"$probe/probe.cxx"
if ! "${CXX:-c++}" -fsanitize="$sanitize" "$probe/probe.cxx" -o "$probe/probe" 2>"$probe/log" ||
  ! "$probe/probe" 2>>"$probe/log"; then
  echo "== sanitize $mode SKIPPED: the $sanitize runtime does not start here:" >&2
  cat "$probe/log" >&2
  exit 0
fi
launchers=()
if command -v ccache >/dev/null; then
  launchers=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
build="build-$mode"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVTKRT_SANITIZE="$sanitize" \
  -DVTKRT_WRAP_PYTHON=OFF -DVTKRT_BUILD_FILTERS=OFF -DVTKRT_BUILD_APPS=OFF \
  -DVTKRT_BUILD_BENCHMARKS=OFF -DVTKRT_BUILD_EXAMPLES=OFF "${launchers[@]}"
cmake --build "$build" -j "$jobs" --target "${targets[@]}"
if [ -n "${VTKRT_SANITIZE_TESTS:-}" ]; then
  read -r -a tests <<<"$VTKRT_SANITIZE_TESTS"
else
  tests=("${default_tests[@]}")
fi
if [ "$mode" = asan ] && [ -f "$mesa_dri" ]; then
  # EGL unloads Mesa's driver at eglTerminate, which leaves the driver's
  # static allocations unreachable and reported as leaks from an unknown
  # module; a preloaded driver stays mapped (ASan's runtime must come first).
  export LD_PRELOAD="$("${CXX:-c++}" -print-file-name=libasan.so) $mesa_dri"
fi
cd "$build" && ctest -j "$jobs" --output-on-failure "${tests[@]}"
