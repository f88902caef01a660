#!/usr/bin/env bash
# The renderer's figures on a GPU machine (the device tool: see benchmarks/RESULTS.md), run from
# the repository root with the code in .gpu/ (src, shaders, demos, benchmarks), the EGL/glvnd
# .debs in .gl/ and the wheels (moderngl, glcontext, pyrr, av) in .whl/. Logs go to $OUT.
set -u
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
log() { echo "== $*" | tee -a "$OUT/summary.log"; }
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade \
    --target /tmp/site .whl/*.whl || exit 1
export PYTHONPATH=/tmp/site:$PWD/.gpu/src PYTHONUNBUFFERED=1
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv | tee -a "$OUT/summary.log"
nproc | tee -a "$OUT/summary.log"
python3 -c "import numpy, numba, PIL, av, moderngl; print('numpy', numpy.__version__, 'numba', numba.__version__, 'moderngl', moderngl.__version__)" 2>&1 | tee -a "$OUT/summary.log"
if ! python3 -c "import moderngl; c = moderngl.create_standalone_context(backend='egl'); print(c.info['GL_RENDERER'], c.info['GL_VERSION'])" 2>&1 | tee -a "$OUT/summary.log" | grep -qi nvidia; then
    export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
    python3 -c "import moderngl; c = moderngl.create_standalone_context(backend='egl'); print(c.info['GL_RENDERER'], c.info['GL_VERSION'])" 2>&1 | tee -a "$OUT/summary.log"
fi
B=.gpu/benchmarks/bench_render.py
T=${T:-timeout 150}
# Hardware path (auto on the GPU): 10 k, 100 k, 1 M at 1080p, with and without readback.
for n in 10000 100000 1000000; do
    log "hardware $n"
    $T python3 $B --spheres $n --size 1920x1080 --frames 60 --rounds 3 --no-record \
        $( [ $n = 1000000 ] && echo --save "$OUT/frame_1M.png" ) 2>&1 | tee "$OUT/hw_$n.log" | tee -a "$OUT/summary.log"
done
log "particle_storm"
$T python3 $B --spheres 1000 --size 1920x1080 --frames 60 --no-bare --demo particle_storm 2>&1 | tee -a "$OUT/summary.log"
# Before: the software path on the same GPU (what issue 27 measured), fewer frames.
for n in 10000 1000000; do
    log "software $n"
    $T python3 $B --path software --spheres $n --size 1920x1080 --frames 8 --rounds 1 \
        --no-record 2>&1 | tee -a "$OUT/summary.log"
done
log "recording (720p side_library, hardware)"
$T python3 $B --spheres 1000 --size 1280x720 --frames 10 --rounds 1 --record-frames 150 2>&1 | tail -4 | tee -a "$OUT/summary.log"
