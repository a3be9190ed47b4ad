#!/usr/bin/env bash
# Installs every Debian 12 package vtkrt needs to build, test and benchmark.
# Idempotent: apt-get skips what is already installed.
set -euo pipefail
PKGS=(
  build-essential cmake ninja-build pkg-config
  libvtk9-dev python3-vtk9 python3 python3-dev
  libglm-dev libopenmesh-dev
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgl-dev
  libembree-dev
  xvfb xauth
  libcli11-dev
  glslang-tools
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
