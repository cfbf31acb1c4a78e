#!/usr/bin/env bash
# Fresh machine to a tested build: installs what is missing, builds, runs every test under ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
# PSS_CMAKE_ARGS: extra CMake options, e.g. "-DPSS_TEST_FUZZ=OFF -DPSS_TEST_SANITIZERS_FULL=OFF" for a
# quicker run without the fuzzers, the TSan stage and the full ASan stage (CI runs them all).
# shellcheck disable=SC2086
"$root/scripts/build.sh" ${PSS_CMAKE_ARGS:-}
ctest --test-dir "${PSS_BUILD_DIR:-$root/build}" --output-on-failure --parallel "$(nproc)" "$@"
