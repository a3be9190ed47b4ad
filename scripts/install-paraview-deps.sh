#!/usr/bin/env bash
# Swaps Debian 12's system VTK stack for its ParaView 5.11 stack (for the
# ParaView plugin build, paraview/), or back with --restore.
#
# python3-paraview and python3-vtk9 both ship the Python package vtkmodules,
# so they conflict: installing ParaView removes python3-vtk9 and libvtk9-dev,
# and --restore reinstalls them (removing python3-paraview and paraview-dev).
# Packages come from apt's cache after the first time, so a swap takes
# seconds.
set -euo pipefail
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
export DEBIAN_FRONTEND=noninteractive
APT=(apt-get -y -q -o Acquire::Retries=3 -o Dpkg::Use-Pty=0 --no-install-recommends)

installed() {
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"
}

# Installs the packages not installed yet (apt-get update only when needed).
install_missing() {
  local missing=()
  for p in "$@"; do
    installed "$p" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    $SUDO apt-get update -q || true # a stale mirror list still has the cache
    $SUDO "${APT[@]}" install "${missing[@]}"
  fi
}

if [ "${1:-}" = "--restore" ]; then
  # The system VTK again (apt removes python3-paraview and what needs it).
  install_missing libvtk9-dev python3-vtk9
  exit 0
fi

# pvbatch/pvserver (paraview), pvpython and ParaView's CMake package
# (python3-paraview, paraview-dev), an X server (Debian's ParaView renders
# through GLX only), MPI for pvbatch/pvserver under mpiexec, and what the
# plugin's vtkrt sources need besides VTK.
install_missing paraview paraview-dev python3-paraview \
  xvfb xauth openmpi-bin libopenmpi-dev \
  build-essential cmake ninja-build libglm-dev libopenmesh-dev libegl-dev python3-numpy
