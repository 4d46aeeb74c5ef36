#!/usr/bin/env bash
# The conversions of the exactness table's other rows on the reference
# material (paper_white/ has the ggx and principled fits): fit
# rgl/paper_white_rgb.bsdf in each model (`brdf fit --metric ngan`) and convert the fit to each target model it is not
# exact in (principled for Mitsuba, ggx-dielectric for pbrt, gltf for glTF,
# MaterialX, USD and Blender), saving the `brdf export --json` report:
#   M.json               the fit
#   M.TARGET.report.json the conversion's report (image error per light set)
# brdf export --list reads the reports (src/table.rs). Several minutes.
#   BRDF_DATA=... BRDF=target/release/brdf bash make.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
: "${BRDF_DATA:?set BRDF_DATA}"
brdf="$(command -v "${BRDF:-brdf}" || true)"
brdf="${brdf:-${BRDF:-brdf}}"
case $brdf in /*) ;; *) brdf="$PWD/$brdf" ;; esac
cd "$here"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
# The material files are not kept (the reports are); written in a scratch
# folder under their plain names.
convert() {
    local m=$1 t=$2 ext=$3
    (cd "$tmp" && "$brdf" export --from "$here/$m.json" --to "$t" "$m.$ext" --json) >"$m.$t.report.json"
}
# The default 12 starts: with 4 the gltf-ext fit stops in the diffuse-only
# basin (roughness 1, specular 0: Ngan L2 0.0196 against 0.0118).
for m in gltf gltf-ext ggx-separable ggx-dielectric ggx-conductor; do
    "$brdf" fit --data "$BRDF_DATA/rgl/paper_white_rgb.bsdf" --model "$m" --metric ngan --save "$m.json" >/dev/null
done
for m in gltf gltf-ext ggx-dielectric ggx-conductor; do convert "$m" mitsuba xml; done
for m in gltf gltf-ext ggx-separable; do convert "$m" pbrt pbrt; done
for m in ggx-separable ggx-dielectric ggx-conductor; do convert "$m" gltf gltf; done
