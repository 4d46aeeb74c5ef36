#!/usr/bin/env bash
# The browser test of the HTML reports: make the page of a fit
# (paper_white RGL with ggx) and of a small batch (2 RGL files x 2 models)
# with the `brdf` binary, then open them in Debian's chromium through
# playwright-core (check.js). Screenshots go to target/report-screenshots/.
#
# usage: run.sh BRDF_BINARY NODE_MODULES   (BRDF_DATA must be set)
set -euo pipefail
brdf="$1"
export NODE_PATH="$2"
root="$(cd "$(dirname "$0")/../../../.." && pwd)"
pages="$root/target/report-pages"
shots="$root/target/report-screenshots"
rm -rf "$pages"
mkdir -p "$pages" "$shots"
paper="$BRDF_DATA/rgl/paper_white_rgb.bsdf"
gem="$BRDF_DATA/rgl/cc_iris_purple_gem_rgb.bsdf"
"$brdf" fit --quiet --data "$paper" --model ggx --starts 4 \
    --save "$pages/paper_white_ggx.json" --report "$pages/paper_white_ggx.html" >/dev/null
"$brdf" batch --quiet --data "$paper" "$gem" --models lambert,ggx --starts 2 \
    --out "$pages/batch" --report
node "$root/crates/brdf-report/tests/browser/check.js" "$shots" \
    "$pages/paper_white_ggx.html" "$pages/batch/report/index.html"
