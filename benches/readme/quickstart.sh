#!/usr/bin/env bash
# Time the README's quick start: run every command of its "Quick start"
# block, exactly as written, in a scratch folder (`brdf` the release build),
# and write their wall times into results/quickstart.md and into the README
# between its `quickstart-times` markers (crates/brdf-cli/tests/cli/readme.rs
# fails when the two differ or a command of the block has no time).
#
#   cargo build --release -p brdf-cli
#   BRDF_DATA=/path/to/data bash benches/readme/quickstart.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
: "${BRDF_DATA:?set BRDF_DATA to the measured data (the quick start fits an RGL file)}"
bin="${BRDF:-$root/target/release/brdf}"
[ -x "$bin" ] || { echo "no $bin: cargo build --release -p brdf-cli first" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# The block's lines, as written.
awk '/^## Quick start/{q=1} q&&/^```bash/{f=1;next} f&&/^```/{exit} f' "$root/README.md" >"$work/block.sh"
[ -s "$work/block.sh" ] || { echo "README.md has no quick-start block" >&2; exit 1; }
brdf() { "$bin" "$@"; }
rows=""
cd "$work"
while IFS= read -r line; do
    case $line in
        brdf\ *)
            start=$(date +%s.%N)
            eval "$line" >/dev/null 2>"$work/stderr" || { cat "$work/stderr" >&2; exit 1; }
            end=$(date +%s.%N)
            cmd="${line%%  #*}"
            rows+="| \`$cmd\` | $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }') |"$'\n'
            ;;
        *) eval "$line" ;;
    esac
done <"$work/block.sh"
table="| command | wall time (s) |
| --- | ---: |
${rows}"
. "$root/benches/readme/write_times.sh"
write_times "$root" quickstart "The README's quick start, timed" \
    "Every command of the README's quick-start block, run as written on \`rgl/paper_white_rgb.bsdf\` with the release build, one after the other; wall time of each (the machine is shared)" \
    "$table"
