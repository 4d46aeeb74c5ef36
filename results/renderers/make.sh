#!/usr/bin/env bash
# The renderer figure of docs/export.md (results/renderers/): a measured RGL material,
# fitted in each renderer's own material and exported exactly: the
# principled fit to Mitsuba 3 (`principled` BSDF), the glTF fit to Blender
# (Principled BSDF, single-scatter GGX; converting the principled fit to it
# is refused for this material, as it changes the render beyond the
# conversion bound, and the refusal says to fit `gltf` directly), rendered by Mitsuba and by Blender Cycles
# beside the measurement in the judge scene, studio light (figure.py).
# Writes the fits MATERIAL.principled.json, MATERIAL.gltf.json, the exports
# MATERIAL.xml, MATERIAL.py, three PNG tiles, renderers.md and
# renderers.json (HDR-FLIP of each render against the measurement).
#   BRDF_DATA=... BRDF=target/release/brdf PYTHON=.../venv-export/bin/python \
#   BLENDER_PYTHON=.../venv-blender/bin/python bash results/renderers/make.sh
# PYTHON needs mitsuba, numpy, flip-evaluator; BLENDER_PYTHON needs bpy.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
: "${BRDF_DATA:?set BRDF_DATA}"
: "${BLENDER_PYTHON:?set BLENDER_PYTHON to a python with bpy}"
brdf="${BRDF:-brdf}"
py="${PYTHON:-python3}"
material="${MATERIAL:-colodur_napoli_4f_rgb}"
data="$BRDF_DATA/rgl/$material.bsdf"
cd "$here"
"$brdf" fit --data "$data" --model principled --save "$material.principled.json" >/dev/null
"$brdf" export --from "$material.principled.json" --to mitsuba "$material.xml" --exact >/dev/null
"$brdf" fit --data "$data" --model gltf --save "$material.gltf.json" >/dev/null
"$brdf" export --from "$material.gltf.json" --to blender "$material.py" --exact >/dev/null
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$BLENDER_PYTHON" ../../crates/brdf-export/tests/reference/cycles_render.py "$tmp" --spp 256 --antialias "$material.py" >&2
"$py" figure.py "$data" "$material.xml" "$tmp/$material.py.studio.seed2.exr" .
