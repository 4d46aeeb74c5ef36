#!/usr/bin/env bash
# Fit times and final costs of the renderer models on the RGL
# files, one thread, default options, RGB:
#
#   BRDF_DATA=... benches/peers/renderer_models.sh [BRDF] > table.md
#
# BRDF is the `brdf` command to time (default: target/release/brdf, built
# with `cargo build --release -p brdf-cli`); pass an older
# build to get the "before" column. Prints one Markdown row per file and
# model: CPU seconds of the whole command (user + sys, loading included;
# on a shared machine far steadier than the wall clock), the fit's own
# wall-clock seconds, Ngan L2, the objective's error, iterations, starts
# (tried, converged, at best) and why it stopped. Compare times as ratios
# within one run.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
: "${BRDF_DATA:?set BRDF_DATA to the measured data folder (with rgl/)}"
brdf="${1:-${CARGO_TARGET_DIR:-$repo/target}/release/brdf}"
models="${MODELS:-principled gltf}"
files="${FILES:-cc_ibiza_sunset_rgb cc_iris_purple_gem_rgb colodur_napoli_4f_rgb paper_white_rgb vch_golden_yellow_rgb}"
export RAYON_NUM_THREADS=1
cpu="$(mktemp)"
trap 'rm -f "$cpu"' EXIT

echo "| file | model | CPU s | fit wall s | ngan L2 | error | iterations | starts | termination |"
echo "| --- | --- | ---: | ---: | ---: | ---: | ---: | --- | --- |"
for model in $models; do
	for f in $files; do
		json="$(/usr/bin/time -f '%U %S' -o "$cpu" "$brdf" fit --data "$BRDF_DATA/rgl/$f.bsdf" --model "$model" --channels rgb --json)"
		secs="$(awk '{ printf "%.3f", $1 + $2 }' "$cpu")"
		jq -r --arg f "$f" --arg m "$model" --arg cpu "$secs" \
			'.fits[0] | "| \($f) | \($m) | \($cpu) | \(.seconds * 1000 | round / 1000) | \(.ngan_l2) | \(.error) | \(.iterations) | \(.starts | map(tostring) | join("/")) | \(.termination) |"' \
			<<<"$json"
	done
done
