#!/bin/bash
# deb under mpirun (DEB_MPI): an uncertainty study, a sweep and an
# optimiser's starts spread over 3 ranks (oversubscribed, on loopback) write
# the directories a single process writes, byte for byte; a rank that meets a sample whose budget fails ends
# the run with that sample's error, a non-zero exit and no directory, and so
# does a rank past --timeout; --shard under mpirun is refused. Skipped (77),
# with the reason, when deb was built without MPI.
# Usage: mpi_test.sh DEB MPIEXEC BUDGET SWEEP_BUDGET
set -u
deb=$1 mpiexec=$2 budget=$3 sweep=$4
if [ -z "$mpiexec" ]; then
  echo "mpi: skipped: deb was built without OpenMPI (install libopenmpi-dev and openmpi-bin, then configure again)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
export SOURCE_DATE_EPOCH=1700000000
run_mpi=("$mpiexec" --oversubscribe -n 3)
[ "$(id -u)" = 0 ] && run_mpi+=(--allow-run-as-root)
fail() { echo "mpi: FAILED: $*"; exit 1; }

"$deb" uncertainty "$budget" -n 200 --method lhs --seed 4 -q -j 2 --out serial || fail "the serial run"
"${run_mpi[@]}" "$deb" uncertainty "$budget" -n 200 --method lhs --seed 4 -q -j 1 --out ranks > ranks.log 2>&1 ||
  { cat ranks.log; fail "the run on 3 ranks"; }
diff -r serial ranks > diff.log || { cat diff.log; fail "3 ranks wrote other files than 1 process"; }
files=$(find ranks -type f | wc -l)
echo "mpi: 3 ranks and 1 process wrote the same $files files, byte for byte"

"$deb" sweep "$sweep" -q --out sweep_serial || fail "the serial sweep"
"${run_mpi[@]}" "$deb" sweep "$sweep" -q -j 1 --out sweep_ranks > sweep.log 2>&1 || { cat sweep.log; fail "the sweep on 3 ranks"; }
diff -r sweep_serial sweep_ranks > diff.log || { cat diff.log; fail "a sweep on 3 ranks wrote other files than 1 process"; }
echo "mpi: a sweep on 3 ranks and in 1 process wrote the same $(find sweep_ranks -type f | wc -l) files"

# The optimiser's starts, one per rank at a time: the same optimum, history and report.
opt=(optimise "$budget" --vary Kv,h --objective z_velocity --starts 4 --max-evaluations 25 --no-plots -q)
"$deb" "${opt[@]}" -j 2 --out opt_serial || fail "the serial optimisation"
"${run_mpi[@]}" "$deb" "${opt[@]}" -j 1 --out opt_ranks > opt.log 2>&1 || { cat opt.log; fail "the optimisation on 3 ranks"; }
diff -r opt_serial opt_ranks > diff.log || { cat diff.log; fail "an optimisation on 3 ranks wrote other files than 1 process"; }
echo "mpi: 4 optimiser starts on 3 ranks and in 1 process wrote the same $(find opt_ranks -type f | wc -l) files"

# s uniform on [-1, 3]: a sample with s < 0 is a negative PSD level.
cat > bad.yaml <<'YAML'
name: bad
parameters:
  s: {value: 2, distribution: {uniform: {min: -1, max: 3}}}
grid: {type: log, min_hz: 1, max_hz: 100, points: 50}
sources:
  - {name: noise, unit: N, spectrum: {type: flat, level: s * 1e-6}}
paths:
  - {name: plant, type: gain, gain: [[1]], input_unit: N, output_unit: um}
contributors:
  - {name: c1, source: noise, path: plant}
outputs:
  - {name: z, signal: y, unit: um}
YAML
"${run_mpi[@]}" "$deb" uncertainty bad.yaml -n 50 -q -j 1 --out bad_out > bad.log 2>&1 && { cat bad.log; fail "a failing sample did not fail the run"; }
grep -q "uncertainty sample" bad.log || { cat bad.log; fail "the error does not name the sample"; }
[ -e bad_out ] && fail "a failed run left a directory"
echo "mpi: a failing sample ends the run: $(grep -m1 'error' bad.log | cut -c1-160)"

# A rank that holds its block past --timeout (a microsecond: every block does)
# ends the run: rank 0 says which, MPI_Abort stops every rank, nothing written.
"${run_mpi[@]}" "$deb" uncertainty "$budget" -n 200 -q -j 1 --timeout 0.000001 --out late > late.log 2>&1 &&
  { cat late.log; fail "a rank past --timeout did not end the run"; }
grep -q "has not returned evaluations" late.log || { cat late.log; fail "--timeout: no clear error"; }
[ -e late ] && fail "a run ended by --timeout left a directory"
echo "mpi: --timeout ends the run: $(grep -m1 'has not returned' late.log | cut -c1-120)"

"${run_mpi[@]}" "$deb" uncertainty "$budget" -n 20 -q --shard 1/2 --out x > shard.log 2>&1 && fail "--shard under mpirun was accepted"
grep -q "give one or the other" shard.log || { cat shard.log; fail "--shard under mpirun: no clear error"; }
echo "mpi: --shard under mpirun refused"
