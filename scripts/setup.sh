#!/usr/bin/env bash
# Set-up shared by scripts/test.sh and scripts/demo.sh: system libraries, then a virtual
# environment with pointmass installed. Safe to run again: it only installs what is missing.
#   EXTRAS=test|all   which pip extras to install (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."

# --- system packages: Mesa's EGL/GL (llvmpipe), Xvfb for windows without a display --------------
# Debian names: EGL and GLX dispatch (libegl1, libgl1), Mesa's vendor libraries and its software
# rasterizer (libegl-mesa0, libglx-mesa0, libgl1-mesa-dri), a virtual X server (xvfb, xauth);
# the sweep's Ray test runs its cluster in a loopback-only network namespace (unshare from
# util-linux, ip and ss from iproute2).
packages=(libegl1 libegl-mesa0 libgl1 libglx-mesa0 libgl1-mesa-dri xvfb xauth util-linux iproute2)
need=()
if command -v dpkg-query >/dev/null; then
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
  done
fi
if [ ${#need[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null && sudo=sudo
  if command -v apt-get >/dev/null; then
    echo "setup: installing system packages: ${need[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
      "${need[@]}" >/dev/null
  else
    echo "setup: please install these system packages (Debian names): ${need[*]}" >&2
  fi
fi

# --- Python environment -------------------------------------------------------------------------
PY=${PYTHON:-python3}
"$PY" -c 'import sys; sys.exit(sys.version_info < (3, 11))' \
  || { echo "setup: pointmass needs Python >= 3.11 (set PYTHON=/path/to/python3.11)" >&2; exit 1; }
if [ ! -x .venv/bin/python ]; then
  if ! "$PY" -m venv .venv 2>/dev/null; then
    # Debian splits venv out of the interpreter package.
    rm -rf .venv
    command -v apt-get >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv
    "$PY" -m venv .venv
  fi
fi
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q -e ".[${EXTRAS:-all}]"

# --- numba's kernels, compiled once into the per-user cache (~/.cache/pointmass/numba) --------
# The demos' first steps would otherwise compile them in the window (about a minute on two
# cores); later runs load them in about a second. POINTMASS_SKIP_WARMUP=1 skips it.
if [ "${POINTMASS_SKIP_WARMUP:-0}" != "1" ]; then
  echo "setup: compiling the physics kernels the demos use (once; a few minutes on 2 cores)"
  .venv/bin/pointmass warmup
fi
