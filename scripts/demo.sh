#!/usr/bin/env bash
# Set up everything on a fresh machine and run the main job: the ball-pit demo in a window, or,
# with no display, a recording of it (ball_pit.mp4). Usage: scripts/demo.sh [DEMO] [--set k=v ...]
set -euo pipefail
cd "$(dirname "$0")/.."
EXTRAS=all bash scripts/setup.sh
demo=${1:-ball_pit}
shift || true
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec .venv/bin/pointmass run "$demo" "$@"
else
  echo "No display: recording $demo to $demo.mp4 instead (pointmass record)."
  exec .venv/bin/pointmass record "$demo" -o "$demo.mp4" --seconds 10 --overwrite "$@"
fi
