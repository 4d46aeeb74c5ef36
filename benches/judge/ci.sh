#!/usr/bin/env bash
# The CI judge: a venv beside the clone with the pinned tools of
# requirements.txt, then test_judge.py against the release `brdf`. The
# Blender route's test renders in Cycles through the bpy venv beside the
# clone (.ci/run installs it), and is skipped where bpy could not be.
set -euo pipefail
cd "$(dirname "$0")/../.."
venv="$(cd .. && pwd)/venv-judge"
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q -r benches/judge/requirements.txt
blender="$(cd .. && pwd)/venv-blender/bin/python"
if [ -z "${BLENDER_PYTHON:-}" ] && "$blender" -c "import bpy" 2>/dev/null; then
    export BLENDER_PYTHON="$blender"
fi
BRDF_BIN="${BRDF_BIN:-$(pwd)/target/release/brdf}" PYTHONDONTWRITEBYTECODE=1 \
    "$venv/bin/python" -m pytest -q -p no:cacheprovider -s --durations=0 benches/judge/test_judge.py
