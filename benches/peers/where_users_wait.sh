#!/usr/bin/env bash
# The commands users wait for, timed, written as JSON
# lines into $1 (a scratch folder) for report.py, and the commands appended
# to $1/commands.txt:
#
#   BRDF_DATA=... benches/peers/where_users_wait.sh OUT
#
# 1. `brdf fit` as users run it (default options: the appearance pipeline
#    for renderer models, with the report-size image errors) and with
#    `--metric ngan` (one fit), principled and glTF on every RGL file, one
#    thread: processor time of the whole command (user + sys) and wall
#    clock, final costs, and the seconds of every candidate of the
#    render-fidelity pipeline; and the same command with Lambert (the
#    command's floor: loading and the report-size renders);
# 2. the full MERL grid (an RGL file resampled by `brdf resample`): the
#    default fit of grey Ashikhmin-Shirley (fit_loop, 1 and 2 threads)
#    against SciPy trf on the same problem (peer_fits + peers.py, same
#    run), and principled RGB with --metric ngan;
# 3. `brdf select` on one RGL file, 1 and 2 threads;
# 4. `brdf batch` over the RGL folder x 5 models, 1 and 2 threads, and
#    `brdf report --batch` of it, one thread;
# 5. criterion: the principled and glTF batch kernels;
# 6. Bagher's SGD as `brdf fit --model sgd` fits it by default (`--metric
#    ngan`, per channel) on every RGL file, one thread, and for appearance
#    on cc_iris_purple_gem, two threads; with PEERS_LONG=1 also SGD for
#    appearance on every RGL file and `brdf reproduce` with the data, two
#    threads (each about half an hour on the shared 2-core machine);
# 7. `brdf fit --for RENDERER` (every model the renderer renders exactly,
#    each fitted for appearance, the closest written) for Mitsuba, Blender
#    and MaterialX on every RGL file, two threads.
#
# Called by run.sh; PEERS_ONLY=where_users_wait runs it alone (about 35 minutes
# on the shared 2-core machine).
set -euo pipefail

out="$1"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
: "${BRDF_DATA:?set BRDF_DATA to the measured data folder (with rgl/)}"
target="${CARGO_TARGET_DIR:-$repo/target}"
py="${PY:-python3}"
d="$out/where_users_wait"
rm -rf "$d"
mkdir -p "$d"
cmds="$out/commands.txt"
cd "$repo"
cargo build --release -p brdf-cli -p brdf-benches --bin brdf --bin fit_loop --bin peer_fits
brdf="$target/release/brdf"
files="${FILES:-cc_ibiza_sunset_rgb cc_iris_purple_gem_rgb colodur_napoli_4f_rgb paper_white_rgb vch_golden_yellow_rgb}"

# One timed command: its JSON output and "cpu wall" seconds as one line.
timed() {
	local tag="$1"
	shift
	/usr/bin/time -f '%U %S %e' -o "$d/time.txt" "$@" >"$d/out.json"
	"$py" - "$tag" "$d/time.txt" "$d/out.json" <<'EOF' >>"$d/runs.jsonl"
import json, sys
tag, t, o = sys.argv[1], sys.argv[2], sys.argv[3]
u, s, e = open(t).read().split()[-3:]
try:
    res = json.load(open(o))
except ValueError:
    res = None
print(json.dumps({"tag": json.loads(tag), "cpu": float(u) + float(s), "wall": float(e), "result": res}))
EOF
}

# 0. The data's renders made once per file into the render cache, so
# every timed command below reads them as a file's second fit does
# (section 1b times the first).
for f in $files; do
	"$brdf" fit --data "$BRDF_DATA/rgl/$f.bsdf" --model lambert --metric ngan --json --quiet >/dev/null
done

# 1. Renderer models on every RGL file, as `brdf fit` runs them.
echo 'RAYON_NUM_THREADS=1 brdf fit --data $BRDF_DATA/rgl/FILE.bsdf --model {principled,gltf} [--metric ngan] --json --quiet' >>"$cmds"
for model in principled gltf; do
	for f in $files; do
		for metric in auto ngan; do
			RAYON_NUM_THREADS=1 timed "{\"kind\": \"rgl\", \"file\": \"$f\", \"model\": \"$model\", \"metric\": \"$metric\"}" \
				"$brdf" fit --data "$BRDF_DATA/rgl/$f.bsdf" --model "$model" --metric "$metric" --json --quiet
		done
	done
done

# 1b. What every `brdf fit` of an RGL file costs besides the fit (loading,
# filtering, the report-size renders of the data and the fit, saving): the
# same command with Lambert, whose fit is one linear solve.
echo 'RAYON_NUM_THREADS=1 brdf fit --data $BRDF_DATA/rgl/FILE.bsdf --model lambert --metric ngan --json --quiet' >>"$cmds"
# The data's renders are kept in the render cache after the fits above
# (`floor`); `--no-cache` renders them again, as the first fit of a file
# does (`floor_cold`).
echo 'RAYON_NUM_THREADS=1 brdf --no-cache fit --data $BRDF_DATA/rgl/FILE.bsdf --model lambert --metric ngan --json --quiet' >>"$cmds"
for f in $files; do
	RAYON_NUM_THREADS=1 timed "{\"kind\": \"floor\", \"file\": \"$f\", \"model\": \"lambert\", \"metric\": \"ngan\"}" \
		"$brdf" fit --data "$BRDF_DATA/rgl/$f.bsdf" --model lambert --metric ngan --json --quiet
	RAYON_NUM_THREADS=1 timed "{\"kind\": \"floor_cold\", \"file\": \"$f\", \"model\": \"lambert\", \"metric\": \"ngan\"}" \
		"$brdf" --no-cache fit --data "$BRDF_DATA/rgl/$f.bsdf" --model lambert --metric ngan --json --quiet
done

# 2. The full MERL grid.
merl="$d/paper_white.binary"
echo 'brdf resample --from $BRDF_DATA/rgl/paper_white_rgb.bsdf --to merl $PEERS_OUT/where_users_wait/paper_white.binary' >>"$cmds"
"$brdf" resample --from "$BRDF_DATA/rgl/paper_white_rgb.bsdf" --to merl "$merl" >/dev/null
for t in 1 2; do
	echo "RAYON_NUM_THREADS=$t fit_loop \$PEERS_OUT/where_users_wait/paper_white.binary ashikhmin-shirley --grey --reps 2 --json" >>"$cmds"
	RAYON_NUM_THREADS=$t "$target/release/fit_loop" "$merl" ashikhmin-shirley --grey --reps 2 --json |
		"$py" -c "import json,sys; r=json.load(sys.stdin); print(json.dumps({'tag': {'kind': 'merl_as', 'threads': $t}, 'result': r}))" >>"$d/runs.jsonl"
done
echo 'RAYON_NUM_THREADS=1 peer_fits --out $PEERS_OUT/where_users_wait/peers --only paper_white_grey_as --solvers bounded; python benches/peers/peers.py $PEERS_OUT/where_users_wait/peers' >>"$cmds"
RAYON_NUM_THREADS=1 "$target/release/peer_fits" --out "$d/peers" --only paper_white_grey_as --solvers bounded >"$d/peer_fits.log"
RAYON_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$py" benches/peers/peers.py "$d/peers" >"$d/peers.log"
echo 'RAYON_NUM_THREADS=1 fit_loop $PEERS_OUT/where_users_wait/paper_white.binary principled --metric ngan --reps 1 --json' >>"$cmds"
RAYON_NUM_THREADS=1 "$target/release/fit_loop" "$merl" principled --metric ngan --reps 1 --json |
	"$py" -c "import json,sys; r=json.load(sys.stdin); print(json.dumps({'tag': {'kind': 'merl_principled', 'threads': 1}, 'result': r}))" >>"$d/runs.jsonl"
rm -f "$merl"

# 3. select on one RGL file.
for t in 1 2; do
	echo "RAYON_NUM_THREADS=$t brdf select --data \$BRDF_DATA/rgl/paper_white_rgb.bsdf --json --quiet" >>"$cmds"
	RAYON_NUM_THREADS=$t timed "{\"kind\": \"select\", \"threads\": $t}" \
		"$brdf" select --data "$BRDF_DATA/rgl/paper_white_rgb.bsdf" --json --quiet
done

# 4. batch over the RGL folder x 5 models.
models="principled,gltf,ggx,ashikhmin-shirley,cook-torrance"
for t in 1 2; do
	rm -rf "$d/batch_$t"
	echo "RAYON_NUM_THREADS=$t brdf batch --data \$BRDF_DATA/rgl --models $models --out \$PEERS_OUT/where_users_wait/batch_$t --quiet" >>"$cmds"
	RAYON_NUM_THREADS=$t timed "{\"kind\": \"batch\", \"threads\": $t, \"fits\": 25}" \
		"$brdf" batch --data "$BRDF_DATA/rgl" --models "$models" --out "$d/batch_$t" --quiet
	cp "$d/batch_$t/summary.csv" "$d/batch_$t.csv"
done

# 4b. The HTML report of the 1-thread batch (25 pages and the index), one
# thread (the batch names its data under $BRDF_DATA, where the report finds
# them).
echo "RAYON_NUM_THREADS=1 brdf report --batch \$PEERS_OUT/where_users_wait/batch_1 --quiet" >>"$cmds"
RAYON_NUM_THREADS=1 timed "{\"kind\": \"report_batch\", \"threads\": 1, \"pages\": 25}" \
	"$brdf" report --batch "$d/batch_1" --quiet
pages=$(find "$d/batch_1/report" -name '*.html' ! -name index.html | wc -l)
if [ "$pages" -ne 25 ]; then
	echo "where_users_wait.sh: brdf report --batch wrote $pages of 25 pages" >&2
	exit 1
fi

# 5. The renderer kernels.
echo "cargo bench -p brdf-benches --bench models -- 'renderer_kernels/' --warm-up-time 2 --measurement-time 5" >>"$cmds"
rm -rf "$target"/criterion/renderer_kernels
cargo bench -p brdf-benches --bench models -- 'renderer_kernels/' --warm-up-time 2 --measurement-time 5 >"$d/kernels.log" 2>&1
mkdir -p "$d/kernels"
for f in "$target"/criterion/renderer_kernels/*/new; do
	name=$(basename "$(dirname "$f")")
	cp "$f/estimates.json" "$d/kernels/$name.estimates.json"
	cp "$f/benchmark.json" "$d/kernels/$name.benchmark.json"
done

# 6. Bagher's SGD.
echo 'RAYON_NUM_THREADS=1 brdf fit --data $BRDF_DATA/rgl/FILE.bsdf --model sgd --json --quiet' >>"$cmds"
for f in $files; do
	RAYON_NUM_THREADS=1 timed "{\"kind\": \"sgd\", \"file\": \"$f\", \"metric\": \"ngan\", \"threads\": 1}" \
		"$brdf" fit --data "$BRDF_DATA/rgl/$f.bsdf" --model sgd --json --quiet
done
appearance_files="cc_iris_purple_gem_rgb"
if [ "${PEERS_LONG:-0}" = 1 ]; then
	appearance_files="$files"
fi
echo "RAYON_NUM_THREADS=2 brdf fit --data \$BRDF_DATA/rgl/FILE.bsdf --model sgd --metric appearance --json --quiet (FILE: $appearance_files)" >>"$cmds"
for f in $appearance_files; do
	RAYON_NUM_THREADS=2 timed "{\"kind\": \"sgd\", \"file\": \"$f\", \"metric\": \"appearance\", \"threads\": 2}" \
		"$brdf" fit --data "$BRDF_DATA/rgl/$f.bsdf" --model sgd --metric appearance --json --quiet
done
if [ "${PEERS_LONG:-0}" = 1 ]; then
	echo 'RAYON_NUM_THREADS=2 brdf reproduce --out $PEERS_OUT/where_users_wait/reproduce --quiet' >>"$cmds"
	/usr/bin/time -f '%U %S %e' -o "$d/time.txt" env RAYON_NUM_THREADS=2 "$brdf" reproduce --out "$d/reproduce" --quiet >/dev/null
	"$py" -c "import json,sys; u,s,e=open(sys.argv[1]).read().split()[-3:]; print(json.dumps({'tag': {'kind': 'reproduce', 'threads': 2}, 'cpu': float(u)+float(s), 'wall': float(e), 'result': None}))" "$d/time.txt" >>"$d/runs.jsonl"
fi

# 7. `brdf fit --for RENDERER`.
echo 'RAYON_NUM_THREADS=2 brdf fit --data $BRDF_DATA/rgl/FILE.bsdf --for {mitsuba,blender,materialx} --out $PEERS_OUT/where_users_wait/for.out --json --quiet' >>"$cmds"
for target in mitsuba blender materialx; do
	for f in $files; do
		RAYON_NUM_THREADS=2 timed "{\"kind\": \"for\", \"file\": \"$f\", \"target\": \"$target\", \"threads\": 2}" \
			"$brdf" fit --data "$BRDF_DATA/rgl/$f.bsdf" --for "$target" --out "$d/for.out" --json --quiet
	done
done
rm -f "$d/time.txt" "$d/out.json" "$d/for.out"
