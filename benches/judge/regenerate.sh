#!/usr/bin/env bash
# Regenerate results/render_fidelity.md and results/render_fidelity/ with
# every configuration the committed table holds: the peer's optimised
# parameters judged again (`peer_inverse.py --rejudge`; `PEER=optimise`
# runs Adam again, which needs drjit's LLVM backend), then every fit.
# Run from anywhere after `cargo build --release`, with BRDF_DATA set,
# PYTHON a python with benches/judge/requirements.txt installed and
# BLENDER_PYTHON one with bpy (the `--for blender` rows, rendered by Cycles).
set -euo pipefail
cd "$(dirname "$0")/../.."
: "${BRDF_DATA:?set BRDF_DATA to the folder holding rgl/}"
: "${BLENDER_PYTHON:?set BLENDER_PYTHON to a python with bpy}"
py="${PYTHON:-python3}"
peer=results/render_fidelity/peer.json
if [ "${PEER:-rejudge}" = optimise ]; then
    "$py" benches/judge/peer_inverse.py --steps 150 --out "$peer"
else
    "$py" benches/judge/peer_inverse.py --rejudge --out "$peer"
fi
configs=principled:default,principled:ngan,gltf:default,ggx:default
configs+=,principled:default:tabulated,sgd:appearance:tabulated,abc:appearance:tabulated
configs+=,abc-smooth:appearance:tabulated,std:appearance:tabulated,dupuy:appearance:tabulated
configs+=,principled:polish,for:mitsuba,for:blender
"$py" benches/judge/render_fidelity.py --configs "$configs" --peer "$peer"
