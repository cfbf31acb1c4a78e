#!/usr/bin/env bash
# Configures and builds PointSetSurfaces (Release) into ${PSS_BUILD_DIR:-build}.
# Extra arguments go to the CMake configure step, e.g. -DPSS_SANITIZE=ON.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PSS_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$build" --parallel "$(nproc)"
