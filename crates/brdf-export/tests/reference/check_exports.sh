#!/usr/bin/env bash
# Check the committed exports with the renderers' own tools and write what
# they said beside the files (the Rust tests read these):
#   mitsuba_check.py        Mitsuba 3 evaluates tests/export/cases.rs and paper_white/*.xml
#                           (snippets pasted into a scene, as a user does)
#   mitsuba_scene_check.py  Mitsuba 3 loads and renders paper_white/*.scene.xml
#   gltf_validate.js        the Khronos glTF validator on paper_white/*.gltf (material
#                           libraries) and mesh/*.gltf (with the preview sphere)
#   materialx_check.py      MaterialX's validate() on paper_white/*.mtlx
#   usd_check.py            USD opens paper_white/*.usda (UsdShade, UsdPreviewSurface inputs)
#   blender_check.py        Blender's bpy runs paper_white/*.py, saves and rereads a .blend
#   render_check.py         checks by rendering (paper_white/render_check.json): each
#                           Mitsuba snippet and scene rendered in Mitsuba, each Blender
#                           script, USD and glTF file rendered in Cycles (cycles_render.py;
#                           the .usda and .gltf through Blender's importers), each MaterialX
#                           document rendered by MaterialX's GLSL renderer (materialx_render.py,
#                           under xvfb-run) under the judge's studio light (Mitsuba also under
#                           its sky), against brdf-render's render of the model the file holds
#                           (examples/judge_exr.rs), by HDR-FLIP
# Needs PYTHON (with mitsuba, numpy, materialx, usd-core, flip-evaluator) and
# NODE_PATH holding gltf-validator; BLENDER_PYTHON (with bpy) for the Blender
# checks, which are skipped with a message without it (render_check.json then
# keeps the committed Cycles answers); xvfb-run (Debian's xvfb) for the
# MaterialX renders, likewise skipped, keeping the committed MaterialX
# answers, where no OpenGL context can be made. JUDGE_EXR: the judge_exr
# example's binary (default: cargo run --release). RENDER_LIGHTS: the light
# sets of the Mitsuba render checks (default studio,sky: brdf-render's sky is
# Mitsuba's sunsky, tabulated; Cycles and MaterialX check studio only). Takes
# about ten minutes (the MaterialX renders on llvmpipe about two).
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
node gltf_validate.js mesh/*.gltf >mesh/gltf_validation.json
"$py" materialx_check.py paper_white/*.mtlx >paper_white/materialx_validation.json
"$py" usd_check.py paper_white/*.usda >paper_white/usd_validation.json
if [ -n "${BLENDER_PYTHON:-}" ]; then
    "$BLENDER_PYTHON" blender_check.py paper_white/*.py >paper_white/blender_check.json
else
    echo "blender check skipped: set BLENDER_PYTHON to a python with bpy; the tests read the committed answers"
fi

# Checks by rendering. brdf-render's renders of every saved model here (the
# fits and their conversions), then the renderers' renders of the exports.
exr_dir="$(mktemp -d)"
trap 'rm -rf "$exr_dir"' EXIT
# One judge_exr run for every model: they share the judge's shading terms.
judge_pairs=()
for m in paper_white/*.json; do
    b=$(basename "$m" .json)
    case $b in *.report | *_validation | *_values | *_scenes | *_check) continue ;; esac
    judge_pairs+=("$here/$m" "$exr_dir/brdf-render/$b")
done
if [ -n "${JUDGE_EXR:-}" ]; then
    "$JUDGE_EXR" "${judge_pairs[@]}"
else
    (cd "$here/../../../.." && cargo run --release -q -p brdf-export --example judge_exr -- "${judge_pairs[@]}")
fi
render_files=(paper_white/*.xml)
kept=() # renderers that cannot run here: their committed answers are kept
if [ -n "${BLENDER_PYTHON:-}" ]; then
    "$BLENDER_PYTHON" cycles_render.py "$exr_dir" --spp 128 paper_white/*.py paper_white/*.usda paper_white/*.gltf >&2
    render_files+=(paper_white/*.py paper_white/*.usda paper_white/*.gltf)
else
    echo "Cycles render checks skipped: set BLENDER_PYTHON to a python with bpy; the committed Cycles answers are kept"
    kept+=(cycles)
fi
# MaterialX's GLSL renderer needs an OpenGL context: Mesa's llvmpipe on an
# Xvfb display (xvfb-run). Without one the committed answers are kept;
# other failures of the render stop the script.
if command -v xvfb-run >/dev/null && xvfb-run -a "$py" materialx_render.py --probe 2>/dev/null; then
    xvfb-run -a "$py" materialx_render.py "$exr_dir" paper_white/*.mtlx >&2
    render_files+=(paper_white/*.mtlx)
else
    echo "MaterialX render checks skipped: no OpenGL context (install xvfb for xvfb-run); the committed MaterialX answers are kept"
    kept+=(materialx)
fi
"$py" render_check.py "$exr_dir" --lights "${RENDER_LIGHTS:-studio,sky}" --spp 1024 "${render_files[@]}" >paper_white/render_check.json.new
if [ ${#kept[@]} -gt 0 ]; then
    # Keep the committed answers of those renderers (the tests check they
    # are for the files as they are).
    "$py" - paper_white/render_check.json paper_white/render_check.json.new "${kept[@]}" <<'PY'
import json, sys
old, new = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
for renderer in sys.argv[3:]:
    if old.get(renderer):
        new[renderer] = old[renderer]
    new["checks"] += [c for c in old["checks"] if c["renderer"] == renderer]
json.dump(new, open(sys.argv[2], "w"), indent=1)
PY
fi
mv paper_white/render_check.json.new paper_white/render_check.json
