#!/usr/bin/env bash
# Packs this build for a GPU machine that has no VTK (see docs/gpu.md): the
# programs and test programs of ./build, the shared libraries they load but
# glibc and the GL/EGL loaders, Debian's glvnd loaders as .debs, and the
# EGL tests' commands, into .gpu/ (git-ignored through .git/info/exclude).
# scripts/gpu/run.sh runs it there.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${VTKRT_BUILD_DIR:-build}
OUT=.gpu
grep -qx '/.gpu/' .git/info/exclude 2>/dev/null || echo '/.gpu/' >> .git/info/exclude
rm -rf "$OUT" /tmp/vtkrt-gpu-bundle
mkdir -p "$OUT/gl" /tmp/vtkrt-gpu-bundle/bin /tmp/vtkrt-gpu-bundle/lib
for f in "$BUILD"/bin/*; do
  case "$f" in *X11*|*BenchBVH|*BenchLocator) ;; *) cp "$f" /tmp/vtkrt-gpu-bundle/bin/ ;; esac
done
cp -a "$BUILD"/lib/libvtkrt*.so* /tmp/vtkrt-gpu-bundle/lib/
for f in /tmp/vtkrt-gpu-bundle/bin/* "$BUILD"/lib/libvtkrt*.so; do ldd "$f"; done |
  awk '$3 ~ /^\// {print $3}' | sort -u |
  grep -v -E '/(libc|libm|libdl|libpthread|librt|ld-linux-x86-64|libGL|libEGL|libOpenGL|libGLX|libGLdispatch|libgbm|libdrm|libglapi|libvtkrt)[.-]' |
  xargs cp -L -t /tmp/vtkrt-gpu-bundle/lib
tar -C /tmp/vtkrt-gpu-bundle -cJf "$OUT/bundle.tar.xz" bin lib
o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/vtkrt-gpu-apt'
mkdir -p /tmp/vtkrt-gpu-apt/partial
apt-get $o update -q > /dev/null
(cd "$OUT/gl" && apt-get $o download libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 2>&1 | grep -v unsandboxed || true)
# The EGL tests' commands (name TAB command), the bundle's programs in place
# of the build's; X11 and Python tests need what such a machine lacks.
(cd "$BUILD" && ctest --show-only=json-v1) | python3 -c '
import json, shlex, sys
build = sys.argv[1]
for t in json.load(sys.stdin)["tests"]:
    cmd = t.get("command")
    area = t["name"].split(".")[0]
    if not cmd or area not in ("pass", "window", "bench", "apps"):
        continue
    line = " ".join(cmd)
    if "X11" in line or "python" in line.lower() or "xvfb" in line.lower() or "glslang" in line:
        continue
    props = {p["name"]: p["value"] for p in t.get("properties", [])}
    pre = "".join("export %s; " % shlex.quote(e) for e in props.get("ENVIRONMENT", []))
    cd = "cd %s; " % shlex.quote(props["WORKING_DIRECTORY"]) if "WORKING_DIRECTORY" in props else ""
    cmd = [c.replace(build + "/bin/", "/tmp/vtkrt-gpu/bin/") for c in cmd]
    print(t["name"] + "\t" + cd + pre + "timeout 150 " + " ".join(shlex.quote(c) for c in cmd))
' "$(cd "$BUILD" && pwd)" > "$OUT/tests.txt"
printf 'SOURCE_DIR=%s\nBUILD_DIR=%s\n' "$PWD" "$(cd "$BUILD" && pwd)" > "$OUT/paths"
echo "$OUT: $(du -sh "$OUT" | cut -f1), $(wc -l < "$OUT/tests.txt") tests"
