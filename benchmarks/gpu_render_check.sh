#!/usr/bin/env bash
# The renderer's figures on a GPU machine (the device tool; see benchmarks/RESULTS.md), in one
# call of a few minutes. Run from the repository root, with:
#   .gpu/       this branch's src, shaders, demos, benchmarks (what is measured),
#   .gpu_base/  optional: the code before (src, shaders, demos), measured at 10 000 spheres
#               in the same call for a before/after on the same machine,
#   .gl/        the EGL/glvnd .debs, .whl/ the wheels (moderngl, glcontext, pyrr, av).
# Prints one table (the lines starting "ROW |") at the end; logs and 1080p frames go to $OUT.
# A try on llvmpipe: SIZES=1000,10000 SIZE=320x180 FRAMES=10 RENDER_PATH=hardware \
#   STORM_SET=count=20000 (PY names the python; OUT the folder).
set -u
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
if [ -d .gl ]; then
    for f in .gl/*.deb; do dpkg -x "$f" /; done
    ldconfig
fi
if [ -d .whl ]; then
    python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade \
        --target /tmp/site .whl/*.whl || exit 1
    SITE=/tmp/site:
else
    SITE=
fi
PY=${PY:-python3}
export PYTHONUNBUFFERED=1 PYTHONWARNINGS=ignore
export PYTHONPATH=$SITE$PWD/.gpu/src
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null
echo "cores: $(nproc)"
gl_name() { $PY -c "import moderngl; c = moderngl.create_standalone_context(backend='egl'); print(c.info['GL_RENDERER'], c.info['GL_VERSION'])"; }
VENDOR=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
if [ -f $VENDOR ] && ! gl_name 2>&1 | grep -qi nvidia; then
    export __EGL_VENDOR_LIBRARY_FILENAMES=$VENDOR
fi
gl_name 2>&1 | tail -1
$PY -c "import numpy, numba, moderngl; print('numpy', numpy.__version__, 'numba', numba.__version__, 'moderngl', moderngl.__version__)"
G=.gpu/benchmarks/gpu_check.py
SIZES=${SIZES:-10000,100000,1000000}
SIZE=${SIZE:-1920x1080}
FRAMES=${FRAMES:-120}
START=$SECONDS
# Before (optional): the code before this branch, 10 000 spheres only (the size whose ratio
# was missed), on the same machine.
if [ -d .gpu_base/src ]; then
    PYTHONPATH=$SITE$PWD/.gpu_base/src timeout ${T_BASE:-90} $PY $G --sizes "${SIZES%%,*}" \
        --size "$SIZE" --frames "$FRAMES" ${RENDER_PATH:+--path $RENDER_PATH} --label before 2>&1 | tee "$OUT/before.log"
    echo "(before: $((SECONDS - START)) s)"
fi
# After: every size, then particle_storm (1 M particles, stepping) in the same process.
timeout ${T_AFTER:-300} $PY $G --sizes "$SIZES" --size "$SIZE" --frames "$FRAMES" \
    ${RENDER_PATH:+--path $RENDER_PATH} --storm --storm-frames ${STORM_FRAMES:-60} \
    ${STORM_SET:+--set $STORM_SET} --label after --save-dir "$OUT" 2>&1 | tee "$OUT/after.log"
echo "(total: $((SECONDS - START)) s)"
echo "== table (frames/s; f/b = full / bare; CPU: ms per call issued back to back, GPU: ms per frame from timer queries)"
grep -h "^ROW | spheres" "$OUT/after.log" | head -1
grep -h "^ROW | [0-9]" "$OUT"/before.log "$OUT/after.log" 2>/dev/null
grep -h "^demo " "$OUT/after.log"
