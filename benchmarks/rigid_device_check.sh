#!/usr/bin/env bash
# Issue 26's and 30's rigid figures on a many-core machine (the device tool's 16 cores), each
# on a quiet core: the random scenes of benchmarks/rigid_fuzz.py (issue 30's 1 000 scenes of
# 300 steps, World() defaults) in JOBS runs side by side, counted as one; then, alone,
# bench_rigid's tower, pyramid and pit with sleep off beside MuJoCo (issue 26 point 10) and
# bench_limits' tiny worlds (one sphere resting on the ground).
#
#   OUT=dir [JOBS=14] [SEEDS=0:1000] [STEPS=300] [BUDGET=60] [ENGINES="..."] \
#       bash benchmarks/rigid_device_check.sh
#
# Logs go to $OUT: fuzz_K.txt per part, fuzz.txt the counts, rigid.txt, limits.txt.
set -uo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-/tmp/rigid_check}
JOBS=${JOBS:-14}
SEEDS=${SEEDS:-0:1000}
STEPS=${STEPS:-300}
BUDGET=${BUDGET:-60}
ENGINES=${ENGINES:-pointmass pointmass-nosleep pointmass-impulses-nosleep mujoco}
PY=${PYTHON:-python3}
mkdir -p "$OUT"
export PYTHONPATH="$PWD/src${PYTHONPATH:+:$PYTHONPATH}"
export NUMBA_NUM_THREADS=1  # one core per run: the parts must not share cores
# compile every kernel once into numba's cache, so the parts load it rather than race
$PY -c "import sys; sys.path.insert(0, 'benchmarks'); import rigid_fuzz; rigid_fuzz.warm_up()"
first=${SEEDS%:*}
last=${SEEDS#*:}
per=$(( (last - first + JOBS - 1) / JOBS ))
start=$(date +%s)
for ((k = 0; k < JOBS; k++)); do
    a=$((first + k * per)); b=$((a + per)); ((b > last)) && b=$last; ((a >= b)) && continue
    $PY benchmarks/rigid_fuzz.py --seeds "$a:$b" --steps "$STEPS" --hang 60 \
        > "$OUT/fuzz_$k.txt" 2>&1 &
done
wait
echo "fuzz: $(( $(date +%s) - start )) s for seeds $SEEDS, $STEPS steps, $JOBS parts"
$PY benchmarks/rigid_fuzz.py --combine "$OUT"/fuzz_*.txt | tee "$OUT/fuzz.txt"
unset NUMBA_NUM_THREADS
$PY benchmarks/bench_rigid.py --scenes tower pyramid pit --budget "$BUDGET" \
    --engines $ENGINES 2>&1 \
    | tee "$OUT/rigid.txt"
$PY benchmarks/bench_limits.py --only-tiny 2>&1 | tee "$OUT/limits.txt"
