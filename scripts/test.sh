#!/usr/bin/env bash
# Fresh machine to a tested build: installs what is missing, builds, runs every test under ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
ctest --test-dir "${PSS_BUILD_DIR:-$root/build}" --output-on-failure --parallel "$(nproc)" "$@"
