#!/usr/bin/env bash
# On a GPU machine, as root, in a copy of this repository that holds the
# .gpu/ folder scripts/gpu/bundle.sh made: installs Debian's glvnd loaders,
# unpacks the build, then runs vtkrtBenchPass (issue 21's command), vtkrt-render
# on the demo, vtkrtBenchFirstFrame and the EGL tests (8 at a time), and
# leaves the results in $1 (default ./gpu-results) and $1.tgz. See docs/gpu.md.
# VTKRT_GPU_BENCH replaces the benchmark's arguments ("skip": no benchmark),
# VTKRT_GPU_FIRST_FRAMES=skip skips the fresh-process first frames,
# VTKRT_GPU_TESTS=N runs the first N tests.
set -uo pipefail
cd "$(dirname "$0")/../.."
RES=$(mkdir -p "${1:-gpu-results}" && cd "${1:-gpu-results}" && pwd)
. .gpu/paths
for f in .gpu/gl/*.deb; do dpkg -x "$f" /; done
ldconfig
nvidia=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f "$nvidia" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-$nvidia}
B=/tmp/vtkrt-gpu
# A run stopped from outside can leave tests running (ctest's timeout puts
# each in a process group of its own): they would share the GPU with these.
pkill -f "$B/bin/" 2>/dev/null && sleep 2
mkdir -p $B && tar -xJf .gpu/bundle.tar.xz -C $B
export LD_LIBRARY_PATH=$B/lib
# The tests read their baselines and data where the build was configured.
[ -e "$SOURCE_DIR" ] || { mkdir -p "$(dirname "$SOURCE_DIR")" && ln -s "$PWD" "$SOURCE_DIR"; }
mkdir -p "$BUILD_DIR/Testing/Temporary"
cut -f2 .gpu/tests.txt | grep -o '^cd [^;]*' | sed 's/^cd //' | sort -u | xargs -r mkdir -p
{
  date; uname -a; nproc
  nvidia-smi --query-gpu=name,driver_version --format=csv 2>/dev/null
  echo "libraries not found:"; ldd $B/bin/vtkrtBenchPass $B/lib/libvtkrtPlugin.so | grep 'not found'
} > "$RES/env.txt" 2>&1
cat "$RES/env.txt"
[ "${VTKRT_GPU_BENCH:-}" = skip ] || timeout 300 $B/bin/vtkrtBenchPass ${VTKRT_GPU_BENCH:---large --sizes 1024,512 --frames 20 --meshes quad,100000,1000000,4000000 --spheres 1000000 --peers impostors --dynamic 1000000,4000000} \
  2>&1 | tee "$RES/bench.txt"
timeout 120 $B/bin/vtkrt-render --demo --size 1024x768 --frames 16 --output "$RES/demo.png" 2>&1 | tee "$RES/demo.txt"
# First frames in fresh processes, shader disk cache empty then filled.
[ "${VTKRT_GPU_FIRST_FRAMES:-}" = skip ] || timeout 240 $B/bin/vtkrtBenchFirstFrame --meshes quad,100000,1000000,4000000 --repeats 3 \
  2>&1 | tee "$RES/first-frames.txt"
mkdir -p /tmp/vtkrt-gpu-tests
# Each test's line goes to tests-live.txt as it ends, and its output is line
# buffered, so that a run stopped midway still says what ended and where
# the others were.
one() {
  local name=${1%%$'\t'*} cmd=${1#*$'\t'} start=$SECONDS result
  # Each command has ctest's timeout already (a run with a second one around
  # it did not finish on the GPU machine: docs/gpu.md).
  if stdbuf -oL -eL bash -c "$cmd" > "/tmp/vtkrt-gpu-tests/$name.log" 2>&1; then
    result="PASS $name"
  else
    result="FAIL $name rc=$?"
  fi
  echo "$result $((SECONDS - start))s" | tee -a "$RES/tests-live.txt"
}
export -f one
export RES
head -n "${VTKRT_GPU_TESTS:-100000}" .gpu/tests.txt | tr '\n' '\0' |
  xargs -0 -P 8 -I{} bash -c 'one "$@"' _ {} | sort > "$RES/tests.txt"
for n in $(awk '$1 == "FAIL" {print $2}' "$RES/tests.txt"); do
  echo "--- $n"; grep -v '^[0-9]*: ' "/tmp/vtkrt-gpu-tests/$n.log" | tail -15
done > "$RES/failures.txt"
cp "$BUILD_DIR"/Testing/Temporary/*.png "$RES/" 2>/dev/null
echo "tests: $(grep -c '^PASS' "$RES/tests.txt") passed, $(grep -c '^FAIL' "$RES/tests.txt") failed"
cat "$RES/failures.txt" | head -c 8000
tar -czf "$RES.tgz" -C "$(dirname "$RES")" "$(basename "$RES")"
