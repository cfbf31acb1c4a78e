#!/usr/bin/env bash
# Fresh machine to first result: installs what is missing, builds, runs the domain demo.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
"${PSS_BUILD_DIR:-$root/build}/bin/pss-domain-demo" "$@"
