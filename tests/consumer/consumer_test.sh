#!/usr/bin/env bash
# The consumer test (CTest `consumer`): installs the build into a temporary
# prefix, builds tests/consumer against it with find_package(deb), runs it on
# a budget and compares the RMS of every output with summary.json of
# `deb run --no-plots` on the same budget. Both run the same code, so they
# must agree to a relative 1e-12. Also: no installed file names the checkout
# or the build tree.
#   consumer_test.sh CMAKE BUILD_DIR SOURCE_DIR DEB CXX BUDGET
set -euo pipefail
cmake_cmd=$1 build_dir=$2 source_dir=$3 deb=$4 cxx=$5 budget=$6
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
work="${TMPDIR:-/tmp}/deb-consumer-$$"
rm -rf "$work"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work"

# Runs a step quietly; its output only when it fails.
step() {
  local name=$1
  shift
  if ! "$@" > "$work/$name.log" 2>&1; then
    echo "consumer test: $name failed: $*" >&2
    cat "$work/$name.log" >&2
    exit 1
  fi
}

step install "$cmake_cmd" --install "$build_dir" --prefix "$work/prefix"
if grep -rlF -e "$source_dir" -e "$build_dir" "$work/prefix" > "$work/paths.txt"; then
  echo "consumer test: installed files name $source_dir or $build_dir:" >&2
  cat "$work/paths.txt" >&2
  exit 1
fi

step configure "$cmake_cmd" -S "$here" -B "$work/build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_PREFIX_PATH="$work/prefix"
step build "$cmake_cmd" --build "$work/build"

step run "$deb" run "$budget" --no-plots -q --out "$work/run"
step summary "$cmake_cmd" -DSUMMARY="$work/run/summary.json" -DOUT="$work/expected.txt" -P "$here/summary_rms.cmake"
"$work/build/budget_rms" "$budget" > "$work/actual.txt"

# Same outputs in the same order, every RMS within a relative 1e-12.
if ! awk -F '\t' '
  NR == FNR { rms[FNR] = $1; name[FNR] = $2; n = FNR; next }
  {
    m = FNR
    if ($2 != name[FNR]) { printf "output %d: %s, summary.json has %s\n", FNR, $2, name[FNR]; bad = 1; next }
    d = $1 - rms[FNR]; if (d < 0) d = -d
    s = rms[FNR] + 0; if (s < 0) s = -s
    if (d > 1e-12 * s) { printf "%s: RMS %s, summary.json %s\n", $2, $1, rms[FNR]; bad = 1 }
  }
  END {
    if (n == 0) { print "summary.json has no outputs"; exit 1 }
    if (m != n) { printf "%d outputs, summary.json has %d\n", m, n; exit 1 }
    exit bad
  }' "$work/expected.txt" "$work/actual.txt" >&2; then
  echo "consumer test: budget_rms disagrees with deb run on $budget" >&2
  exit 1
fi
echo "consumer test: $(wc -l < "$work/actual.txt") outputs of $budget agree with deb run"
