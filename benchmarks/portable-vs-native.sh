#!/usr/bin/env bash
# The portable default build against a native one, in one run on one machine:
#
#   benchmarks/portable-vs-native.sh [--rows PATTERN] [--runs N] [--data DIR] [--work DIR]
#
# Builds the core and pss-bench twice from this checkout (core only, Release): the default
# (x86-64 baseline, plus the core's x86-64-v3 copy that glibc's loader takes where the CPU runs
# it) and -DPSS_NATIVE_ARCH=ON (-march=native). Then runs `pss-bench --rows PATTERN` with each,
# alternated, N times (default 3), and prints each row's items/s per run, the medians and the
# default's median over the native's. Defaults: --rows "bunny com", --data ../shared/data,
# --work /tmp/pss-portable-vs-native (the two build folders, reused when present).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
rows="bunny com"
runs=3
data="$here/../shared/data"
work="${TMPDIR:-/tmp}/pss-portable-vs-native"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --rows) rows="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --data) data="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    *) echo "usage: $0 [--rows PATTERN] [--runs N] [--data DIR] [--work DIR]" >&2; exit 2 ;;
  esac
done

build() { # build NAME CMAKE_ARGS...
  local dir="$work/$1"; shift
  cmake -S "$here" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DPSS_ENABLE_VTK=OFF -DPSS_BUILD_TESTING=OFF \
    -DPSS_BUILD_EXAMPLES=OFF "$@" > "$dir.configure.log" 2>&1 || { cat "$dir.configure.log"; exit 1; }
  cmake --build "$dir" --target pss-bench -j "$(nproc)" > "$dir.build.log" 2>&1 || { tail -40 "$dir.build.log"; exit 1; }
}
mkdir -p "$work"
echo "building the default and the native build in $work ..."
build default -DPSS_NATIVE_ARCH=OFF
build native -DPSS_NATIVE_ARCH=ON

results="$work/results.$$.txt"
: > "$results"
for ((run = 1; run <= runs; ++run)); do
  for name in default native; do
    # A row line: its name (words), then items and items/s.
    "$work/$name/bin/pss-bench" --data "$data" --rows "$rows" | awk -v build="$name" -v run="$run" '
      { for (i = 1; i <= NF; ++i) if ($i ~ /^[0-9]+$/) break
        if (i > 1 && i + 1 <= NF && $(i + 1) ~ /^[0-9]+$/) {
          row = $1; for (j = 2; j < i; ++j) row = row " " $j
          print build "\t" run "\t" row "\t" $(i + 1) } }' >> "$results"
  done
  echo "run $run of $runs done"
done

python3 - "$results" <<'PY'
import collections, statistics, sys
table = collections.defaultdict(lambda: collections.defaultdict(list))
order = []
for line in open(sys.argv[1]):
    build, run, row, rate = line.rstrip("\n").split("\t")
    if row not in order:
        order.append(row)
    table[row][build].append(int(rate))
print("| row | default, items/s per run | native, items/s per run | default / native (medians) |")
print("| --- | ---: | ---: | ---: |")
for row in order:
    d, n = table[row]["default"], table[row]["native"]
    ratio = statistics.median(d) / statistics.median(n) if d and n else float("nan")
    print("| %s | %s | %s | %.3f |" % (row, " / ".join(format(x, ",") for x in d),
                                       " / ".join(format(x, ",") for x in n), ratio))
PY
