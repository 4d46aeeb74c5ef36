#!/usr/bin/env bash
# Time the README's two set-up commands as a newcomer meets them: in a
# fresh clone of the committed tree (nothing built yet, so the first
# command's time includes compiling the workspace), without BRDF_DATA,
# each command run exactly as the README writes it. Writes the times into
# results/setup.md and into the README between its `setup-times` markers
# (crates/brdf-cli/tests/cli/readme.rs fails when the two differ or a set-up
# command has no time).
#
#   bash benches/readme/setup.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
git clone -q "$root" "$work/clone"
# The set-up section's command blocks (the plain ``` blocks), in order.
awk '/^## Set-up/{s=1;next} s&&/^## /{exit} s&&/^```$/{f=!f;next} s&&f' "$root/README.md" >"$work/commands"
[ "$(wc -l <"$work/commands")" -eq 2 ] || { echo "README.md's set-up section must hold two one-line command blocks" >&2; exit 1; }
rows=""
cd "$work/clone"
while IFS= read -r cmd; do
    start=$(date +%s)
    env -u BRDF_DATA -u CARGO_TARGET_DIR bash -c "$cmd" >/dev/null 2>"$work/stderr" || { tail -20 "$work/stderr" >&2; exit 1; }
    end=$(date +%s)
    rows+="| \`$cmd\` | $(( (end - start + 30) / 60 )) |"$'\n'
done <"$work/commands"
table="| command (fresh clone, no data) | wall time (min) |
| --- | ---: |
${rows}"
. "$root/benches/readme/write_times.sh"
write_times "$root" setup "The README's set-up commands, timed" \
    "The two commands of the README's set-up, run as written one after the other in a fresh clone without \`BRDF_DATA\`: the first compiles the workspace, the second its tests. Wall time rounded to the minute" \
    "$table"
