#!/usr/bin/env bash
# Check the committed exports with the renderers' own tools and write what
# they said beside the files (the Rust tests read these):
#   mitsuba_check.py  Mitsuba 3 evaluates tests/cases.rs and paper_white/*.xml
#   gltf_validate.js  the Khronos glTF validator on paper_white/*.gltf
#   materialx_check.py  MaterialX's validate() on paper_white/*.mtlx
# Needs PYTHON (with mitsuba, numpy, materialx) and NODE_PATH holding
# gltf-validator. Takes about 10 seconds.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
py="${PYTHON:-python3}"
cd "$here"
"$py" mitsuba_check.py mitsuba_cases.json >mitsuba_values.json.new
mv mitsuba_values.json.new mitsuba_values.json
"$py" - <<'PY' >paper_white/mitsuba_cases.json
import glob, json
print(json.dumps([{"file": f, "xml": open(f).read()} for f in sorted(glob.glob("paper_white/*.xml"))]))
PY
"$py" mitsuba_check.py paper_white/mitsuba_cases.json >paper_white/mitsuba_values.json
rm paper_white/mitsuba_cases.json
node gltf_validate.js paper_white/*.gltf >paper_white/gltf_validation.json
"$py" materialx_check.py paper_white/*.mtlx >paper_white/materialx_validation.json
