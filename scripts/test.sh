#!/usr/bin/env bash
# Set up everything on a fresh machine and run the whole test suite: physics, offscreen
# rendering (EGL) and real windows (under Xvfb). Extra arguments go to pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
EXTRAS=test bash scripts/setup.sh
# The documentation site (mkdocs.yml -> site/): --strict fails on any warning (a broken link,
# a docstring the API reference cannot read). NO_MKDOCS_2_WARNING: material's notice.
NO_MKDOCS_2_WARNING=1 .venv/bin/mkdocs build --strict --quiet
# GL and window tests must run here, never skip: the fixtures fail instead of skipping.
export POINTMASS_REQUIRE_GL=1
exec xvfb-run -a -s "-screen 0 1920x1080x24" .venv/bin/python -m pytest "$@"
