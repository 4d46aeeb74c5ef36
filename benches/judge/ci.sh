#!/usr/bin/env bash
# The CI judge: a venv beside the clone with the pinned tools of
# requirements.txt, then test_judge.py against the release `brdf`.
set -euo pipefail
cd "$(dirname "$0")/../.."
venv="$(cd .. && pwd)/venv-judge"
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q -r benches/judge/requirements.txt
BRDF_BIN="${BRDF_BIN:-$(pwd)/target/release/brdf}" PYTHONDONTWRITEBYTECODE=1 \
    "$venv/bin/python" -m pytest -q -p no:cacheprovider -s benches/judge/test_judge.py
