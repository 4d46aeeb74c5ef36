#!/usr/bin/env bash
# Regenerate the paper_white export fixtures: fit rgl/paper_white_rgb.bsdf
# in GGX and in principled (`brdf fit`), export each fit to every target
# (`brdf export`, converting for appearance where the target has no exact
# equivalent, the converted models and reports saved beside), then check
# the files with the renderers' own tools (../check_exports.sh). Files:
#   M.xml M.pbrt M.gltf M.mtlx M.usda M.py   --to mitsuba|pbrt|gltf|materialx|usd|blender
#   M.openpbr.mtlx                           --to materialx --surface openpbr
#   M.scene.xml                              --to mitsuba --scene (studio light)
#   (the .gltf files are written with --no-mesh: the material alone)
#   ../mesh/paper_white_rgb.gltf             principled's glTF conversion with its preview sphere
#   ../mesh/film_iridescence.gltf            ../mesh/film_iridescence.json (gltf-iridescence), exact
#   M.KIND.json, M.KIND.report.json          the conversion, where there is one
# Takes several minutes (the principled fit, the conversions).
#   BRDF_DATA=... BRDF=target/release/brdf bash make.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
: "${BRDF_DATA:?set BRDF_DATA}"
brdf="${BRDF:-brdf}"
cd "$here"
# export MODEL KIND FILE ARGS...: exact when possible, else converted; a
# conversion beyond brdf export's limits is forced (the files are fixtures of
# the writers; the report says `"forced": true`).
export_one() {
    local m=$1 kind=$2 file=$3
    shift 3
    if "$brdf" export --from "$m.json" "$@" "$file" --exact >/dev/null 2>&1; then
        rm -f "$m.$kind.json" "$m.$kind.report.json"
    else
        "$brdf" export --from "$m.json" "$@" "$file" --save-converted "$m.$kind.json" --json --force >"$m.$kind.report.json"
    fi
}
for m in ggx principled; do
    "$brdf" fit --data "$BRDF_DATA/rgl/paper_white_rgb.bsdf" --model "$m" --metric ngan --starts 4 --save "$m.json" >/dev/null
    for t in mitsuba pbrt gltf materialx usd blender; do
        ext=$(case $t in mitsuba) echo xml;; pbrt) echo pbrt;; gltf) echo gltf;; materialx) echo mtlx;; usd) echo usda;; blender) echo py;; esac)
        # glTF: the material alone (Cycles renders it on the judge's sphere).
        export_one "$m" "$t" "$m.$ext" --to "$t" $([ "$t" = gltf ] && echo --no-mesh)
    done
    export_one "$m" openpbr "$m.openpbr.mtlx" --to materialx --surface openpbr
    export_one "$m" scene "$m.scene.xml" --to mitsuba --scene
done
# A glTF file with its preview sphere (the default), for the validator.
"$brdf" export --from principled.gltf.json --to gltf --exact ../mesh/paper_white_rgb.gltf >/dev/null
# glTF's thin film (KHR_materials_iridescence), a hand-chosen model.
"$brdf" export --from ../mesh/film_iridescence.json --to gltf --name film_iridescence \
    ../mesh/film_iridescence.gltf >/dev/null
bash ../check_exports.sh
