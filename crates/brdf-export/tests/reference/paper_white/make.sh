#!/usr/bin/env bash
# Regenerate the paper_white export fixtures: fit rgl/paper_white_rgb.bsdf
# in GGX and in principled (`brdf fit`), export each fit to the four formats
# (`brdf export`, converting where the target has no exact equivalent, the
# converted models saved beside), then check the files with the renderers'
# own tools (../check_exports.sh). Takes about 2 minutes (the principled fit).
#   BRDF_DATA=... BRDF=target/release/brdf bash make.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
: "${BRDF_DATA:?set BRDF_DATA}"
brdf="${BRDF:-brdf}"
cd "$here"
for m in ggx principled; do
    "$brdf" fit --data "$BRDF_DATA/rgl/paper_white_rgb.bsdf" --model "$m" --starts 4 --save "$m.json" >/dev/null
    for t in mitsuba pbrt gltf materialx; do
        ext=$(case $t in mitsuba) echo xml;; pbrt) echo pbrt;; gltf) echo gltf;; materialx) echo mtlx;; esac)
        if "$brdf" export --from "$m.json" --to "$t" "$m.$ext" --exact >/dev/null 2>&1; then
            rm -f "$m.$t.json"
        else
            "$brdf" export --from "$m.json" --to "$t" "$m.$ext" --save-converted "$m.$t.json" --json >"$m.$t.report.json"
        fi
    done
done
bash ../check_exports.sh
