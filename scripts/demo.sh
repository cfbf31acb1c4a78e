#!/usr/bin/env bash
# Fresh machine to first result: installs what is missing, builds, and runs the main demo, which
# reproduces the figures of Amenta & Kil, "The Domain of a Point Set Surface" (VTK files and PNG
# images in build/paper-figures) and prints the table of measured numbers and the checked claims.
# Arguments go to pss-paper-figures (--help lists them; e.g. --out DIR, --no-render, --check).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
build="${PSS_BUILD_DIR:-$root/build}"
"$build/bin/pss-paper-figures" --out "$build/paper-figures" "$@"
