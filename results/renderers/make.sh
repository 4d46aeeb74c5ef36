#!/usr/bin/env bash
# The renderer figure of README.md and docs/export.md (results/renderers/): a
# measured film (RGL cc_ibiza_sunset, a paint whose highlight is another hue
# than its body), fitted for each renderer in one command (`brdf fit --for
# mitsuba`, `brdf fit --for blender`, `brdf fit --for materialx`: among the
# models that renderer renders exactly, the one whose render is closest to
# the data), rendered by Mitsuba 3, by Blender Cycles and by MaterialX's GLSL
# renderer (under xvfb-run) beside the measurement in the judge scene,
# studio light (figure.py).
# Writes the fits MATERIAL.mitsuba.json, MATERIAL.blender.json,
# MATERIAL.materialx.json, the materials MATERIAL.xml, MATERIAL.py,
# MATERIAL.mtlx, four PNG tiles, renderers.md and renderers.json (HDR-FLIP
# of each render against the measurement).
#   BRDF_DATA=... BRDF=target/release/brdf PYTHON=.../venv-export/bin/python \
#   BLENDER_PYTHON=.../venv-blender/bin/python bash results/renderers/make.sh
# PYTHON needs mitsuba, numpy, flip-evaluator, materialx; BLENDER_PYTHON
# needs bpy; xvfb-run (Debian's xvfb) gives MaterialX its display.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
: "${BRDF_DATA:?set BRDF_DATA}"
: "${BLENDER_PYTHON:?set BLENDER_PYTHON to a python with bpy}"
brdf="${BRDF:-brdf}"
py="${PYTHON:-python3}"
material="${MATERIAL:-cc_ibiza_sunset_rgb}"
data="$BRDF_DATA/rgl/$material.bsdf"
cd "$here"
rm -f ./*.principled.json ./*.gltf.json
"$brdf" fit --data "$data" --for mitsuba --out "$material.xml" --save "$material.mitsuba.json" >/dev/null
"$brdf" fit --data "$data" --for blender --out "$material.py" --save "$material.blender.json" >/dev/null
"$brdf" fit --data "$data" --for materialx --out "$material.mtlx" --save "$material.materialx.json" >/dev/null
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$BLENDER_PYTHON" ../../crates/brdf-export/tests/reference/cycles_render.py "$tmp" --spp 256 --antialias "$material.py" >&2
xvfb-run -a "$py" ../../crates/brdf-export/tests/reference/materialx_render.py "$tmp" "$material.mtlx" >&2
"$py" figure.py "$data" "$material.xml" "$tmp/$material.py.studio.seed2.exr" \
    "$tmp/$material.mtlx.studio.seed2.exr" .
