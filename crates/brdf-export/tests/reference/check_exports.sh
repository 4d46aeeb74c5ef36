#!/usr/bin/env bash
# Check the committed exports with the renderers' own tools and write what
# they said beside the files (the Rust tests read these):
#   mitsuba_check.py        Mitsuba 3 evaluates tests/cases.rs and paper_white/*.xml
#                           (snippets pasted into a scene, as a user does)
#   mitsuba_scene_check.py  Mitsuba 3 loads and renders paper_white/*.scene.xml
#   gltf_validate.js        the Khronos glTF validator on paper_white/*.gltf
#   materialx_check.py      MaterialX's validate() on paper_white/*.mtlx
#   usd_check.py            USD opens paper_white/*.usda (UsdShade, UsdPreviewSurface inputs)
#   blender_check.py        Blender's bpy runs paper_white/*.py, saves and rereads a .blend
# Needs PYTHON (with mitsuba, numpy, materialx, usd-core) and NODE_PATH
# holding gltf-validator; BLENDER_PYTHON (with bpy) for the Blender check,
# which is skipped with a message without it. Takes about 30 seconds.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
py="${PYTHON:-python3}"
cd "$here"
"$py" mitsuba_check.py mitsuba_cases.json >mitsuba_values.json.new
mv mitsuba_values.json.new mitsuba_values.json
"$py" - <<'PY' >paper_white/mitsuba_cases.json
import glob, json
files = [f for f in sorted(glob.glob("paper_white/*.xml")) if not f.endswith(".scene.xml")]
print(json.dumps([{"file": f, "xml": open(f).read()} for f in files]))
PY
"$py" mitsuba_check.py paper_white/mitsuba_cases.json >paper_white/mitsuba_values.json
rm paper_white/mitsuba_cases.json
"$py" mitsuba_scene_check.py paper_white/*.scene.xml >paper_white/mitsuba_scenes.json
node gltf_validate.js paper_white/*.gltf >paper_white/gltf_validation.json
"$py" materialx_check.py paper_white/*.mtlx >paper_white/materialx_validation.json
"$py" usd_check.py paper_white/*.usda >paper_white/usd_validation.json
if [ -n "${BLENDER_PYTHON:-}" ]; then
    "$BLENDER_PYTHON" blender_check.py paper_white/*.py >paper_white/blender_check.json
else
    echo "blender check skipped: set BLENDER_PYTHON to a python with bpy; the tests read the committed answers"
fi
