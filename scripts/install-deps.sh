#!/usr/bin/env bash
# Installs what PointSetSurfaces needs from Debian 12's archive, and nothing that is already there.
# Works as root, or through sudo otherwise. Safe to run any number of times.
set -euo pipefail

# ParaView 5.11's development package brings the VTK 9.2 we build against (Debian's libvtk9-dev
# conflicts with python3-paraview); its CMake config needs python3-paraview and qtbase5-dev, and
# the VTK components we use need libdouble-conversion-dev, which paraview-dev does not pull in.
# Building the plugin also needs MPI (ParaView's VTK::mpi links MPI::MPI_C), Qt5Help and Qt's
# xmlpatterns (the server-manager XML is turned into help pages); mpiexec runs the two-rank pvbatch
# test. The fuzz targets (tests/fuzz)
# need clang and its compiler-rt (libFuzzer and the sanitizer runtimes). The numpy functions of the
# Python package (and their tests, in Debian's python3 and pvpython) need python3-numpy.
packages=(
  build-essential cmake pkg-config
  clang libclang-rt-14-dev
  libeigen3-dev libnanoflann-dev libgtest-dev
  paraview-dev python3-paraview python3-numpy qtbase5-dev libdouble-conversion-dev
  mpi-default-dev mpi-default-bin qttools5-dev qtxmlpatterns5-dev-tools
  xvfb xauth
  liblzf-dev doxygen
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages are present"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "install-deps: missing packages (${missing[*]}) and neither root nor sudo is available" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
"${as_root[@]}" apt-get update -q
DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -q "${missing[@]}"
