#!/usr/bin/env bash
# Set-up shared by scripts/test.sh and scripts/demo.sh: system libraries, then a virtual
# environment with pointmass installed. Safe to run again: it only installs what is missing.
#   EXTRAS=test|all   which pip extras to install (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."

# --- system packages: Mesa's EGL/GL (llvmpipe), Xvfb for windows without a display --------------
need=()
ldconfig -p 2>/dev/null | grep -q 'libEGL.so.1' || need+=(libegl1)
[ -e /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so ] || [ -e /usr/lib/aarch64-linux-gnu/dri/swrast_dri.so ] \
  || need+=(libgl1-mesa-dri libegl-mesa0)
ldconfig -p 2>/dev/null | grep -q 'libGL.so.1' || need+=(libgl1 libglx-mesa0)
command -v xvfb-run >/dev/null || need+=(xvfb xauth)
if [ ${#need[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null && sudo=sudo
  if command -v apt-get >/dev/null; then
    echo "setup: installing system packages: ${need[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${need[@]}" >/dev/null
  else
    echo "setup: please install these system packages (Debian names): ${need[*]}" >&2
  fi
fi

# --- Python environment -------------------------------------------------------------------------
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$PY" -m venv .venv
fi
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q -e ".[${EXTRAS:-all}]"
