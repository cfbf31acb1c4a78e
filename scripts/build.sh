#!/usr/bin/env bash
# Configures and builds PointSetSurfaces with the release preset (CMakePresets.json: Release, every
# stage's tests) into ${PSS_BUILD_DIR:-build}, with every core (or $CMAKE_BUILD_PARALLEL_LEVEL).
# Extra arguments go to the CMake configure step, e.g. -DPSS_BUILD_PARAVIEW_PLUGIN=OFF.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PSS_BUILD_DIR:-$root/build}"
cmake -S "$root" --preset release -B "$build" "$@"
cmake --build "$build" --parallel "${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}"
