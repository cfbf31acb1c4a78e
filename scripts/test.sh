#!/usr/bin/env bash
# Fresh machine to a tested build: installs what is missing, builds (scripts/build.sh), then runs
# the test stages under ctest. Stages are ctest labels (cmake/PssTesting.cmake):
#
#   scripts/test.sh           every stage, one after another (what .ci/run runs):
#                               1. plain:     unit pipeline cli paper paraview install python portable docs bunny
#                               2. sanitizer: builds the ASan+UBSan copy, alone, runs its suites; the same with TSan
#                               3. fuzz:      builds the libFuzzer targets with clang, alone, runs each fuzzer
#                               4. clang:     builds the unit, pipeline and cli suites with clang, alone, runs them
#   scripts/test.sh --quick   the developer loop: all but the sanitizer, fuzz, clang and bunny stages
#
# A nested build (sanitized copy, fuzz targets, clang copy) is a ctest test marked RUN_SERIAL: it runs with
# every core while no test runs. Other arguments go to each ctest run (e.g. -R Circle, -L unit).
# Environment: PSS_BUILD_DIR (default build/), PSS_CMAKE_ARGS (extra configure options, e.g.
# "-DPSS_TEST_FUZZ=OFF"), CMAKE_BUILD_PARALLEL_LEVEL (build jobs, default every core),
# PSS_TEST_JOBS (tests run side by side, default every core).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
quick=0
args=()
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    *) args+=("$arg") ;;
  esac
done

"$root/scripts/install-deps.sh"
# shellcheck disable=SC2086
"$root/scripts/build.sh" ${PSS_CMAKE_ARGS:-}
build="${PSS_BUILD_DIR:-$root/build}"
jobs="${PSS_TEST_JOBS:-$(nproc)}"

failed=()
summary=()
stage() {
  local name="$1"
  shift
  local start=$SECONDS status=passed
  echo "test.sh: stage '$name' (ctest $*)"
  if ! ctest --test-dir "$build" --output-on-failure --parallel "$jobs" "$@" "${args[@]}"; then
    status=FAILED
    failed+=("$name")
  fi
  summary+=("stage '$name': $status in $((SECONDS - start)) s")
}

if [ "$quick" -eq 1 ]; then
  stage quick -LE 'sanitizer|fuzz|clang|bunny'
else
  stage plain -LE 'sanitizer|fuzz|clang'
  stage sanitizer -L sanitizer
  stage fuzz -L fuzz
  stage clang -L clang
fi

printf 'test.sh: %s\n' "${summary[@]}"
if [ ${#failed[@]} -ne 0 ]; then
  echo "test.sh: FAILED stages: ${failed[*]}" >&2
  exit 1
fi
echo "test.sh: every stage passed"
