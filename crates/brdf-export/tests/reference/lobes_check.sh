#!/usr/bin/env bash
# Check the coloured-lobe Mitsuba fixtures (lobes/M.xml, the exports of the
# hand-chosen models lobes/M.json, written by
# `LOBES_WRITE=1 cargo test --release -p brdf-export --test export lobes::`) with
# Mitsuba 3 itself, writing what it said beside them (tests/export/lobes.rs reads it):
#   lobes/mitsuba_values.json  mitsuba_check.py: Mitsuba's eval of each M.xml
#                              at 300 direction pairs and at the normal
#   lobes/usd_check.json       usd_materialx_check.py: USD's reading of each
#                              M.usda against MaterialX's of M.mtlx
#   lobes/render_check.json    render_check.py: Mitsuba's render of each M.xml
#                              on the judge sphere (studio and sky), with
#                              BLENDER_PYTHON (a python with bpy) Cycles' render
#                              of each M.py (cycles_render.py, studio), and
#                              with an X display (xvfb-run) MaterialX's GLSL
#                              render of each M.mtlx (materialx_render.py,
#                              studio), beside
#                              brdf-render's (examples/judge_exr.rs) of M.json,
#                              by HDR-FLIP
# Needs PYTHON with mitsuba, numpy, materialx, usd-core, flip-evaluator. JUDGE_EXR: the judge_exr
# example's binary (default: cargo run --release). A few minutes.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
py="${PYTHON:-python3}"
cd "$here"
"$py" - <<'PY' >lobes/mitsuba_cases.json
import glob, json
print(json.dumps([{"file": f, "xml": open(f).read()} for f in sorted(glob.glob("lobes/*.xml"))]))
PY
"$py" mitsuba_check.py lobes/mitsuba_cases.json >lobes/mitsuba_values.json
rm lobes/mitsuba_cases.json
"$py" usd_materialx_check.py lobes/*.usda >lobes/usd_check.json
exr_dir="$(mktemp -d)"
trap 'rm -rf "$exr_dir"' EXIT
# One judge_exr run for every model: they share the judge's shading terms.
judge_pairs=()
for m in lobes/*.json; do
    b=$(basename "$m" .json)
    case $b in render_check | mitsuba_values | usd_check) continue ;; esac
    judge_pairs+=("$here/$m" "$exr_dir/brdf-render/$b")
done
if [ -n "${JUDGE_EXR:-}" ]; then
    "$JUDGE_EXR" "${judge_pairs[@]}"
else
    (cd "$here/../../../.." && cargo run --release -q -p brdf-export --example judge_exr -- "${judge_pairs[@]}")
fi
render_files=(lobes/*.xml)
if [ -n "${BLENDER_PYTHON:-}" ]; then
    "$BLENDER_PYTHON" cycles_render.py "$exr_dir" --spp 128 lobes/*.py >&2
    "$BLENDER_PYTHON" film_cycles_mirror.py >&2 # film/cycles_mirror.json (tests/export/film_cycles.rs)
    render_files+=(lobes/*.py)
else
    echo "Cycles render checks skipped: set BLENDER_PYTHON to a python with bpy"
fi
if command -v xvfb-run >/dev/null && xvfb-run -a "$py" materialx_render.py --probe 2>/dev/null; then
    xvfb-run -a "$py" materialx_render.py "$exr_dir" lobes/*.mtlx >&2
    render_files+=(lobes/*.mtlx)
else
    echo "MaterialX render checks skipped: no OpenGL context (install xvfb for xvfb-run)"
fi
"$py" render_check.py "$exr_dir" --lights "${RENDER_LIGHTS:-studio,sky}" --spp 1024 "${render_files[@]}" >lobes/render_check.json.new
mv lobes/render_check.json.new lobes/render_check.json
