#!/usr/bin/env bash
# Regenerate results/performance.md: our fits timed beside peer libraries on
# the same problems, and the commands users wait for.
#
#   BRDF_DATA=... benches/peers/run.sh
#
# 1. a Python venv OUTSIDE the repository ($PEERS_VENV, default
#    venv-peers beside the clone) with benches/peers/requirements.txt;
# 2. peer_fits (release): builds the problems, exports them to the scratch
#    folder ($PEERS_OUT, default $CARGO_TARGET_DIR/peers or target/peers)
#    and fits them with the Rust solvers;
# 3. peers.py: checks the NumPy model against Rust's, fits with SciPy
#    (trf in the box, lm unbounded) and evaluates the one shared cost at
#    every solver's result;
# 4. IRLS side by side: irls_peer (release) writes the IRLS designs to
#    $PEERS_OUT/irls/designs and times brdf_solve::irls on them
#    ($PEERS_OUT/irls/rust.jsonl); irls_statsmodels.py times statsmodels
#    RLM on the same files ($PEERS_OUT/irls/statsmodels.jsonl);
# 5. profiles of the full-grid grey fit (perf, else callgrind on CUReT);
# 6. report.py writes results/performance.md.
#
# 7. where_users_wait.sh: the commands users wait for (default `brdf fit` of the
#    renderer models on every RGL file, the full MERL grid against SciPy,
#    select, batch on 1 and 2 threads, the renderer kernels, Bagher's SGD,
#    `brdf fit --for` Mitsuba, Blender and MaterialX; PEERS_LONG=1 adds SGD
#    for appearance on every file and `brdf reproduce`).
#
# PEERS_ONLY=irls runs step 4 alone (no fit peers, no profiles) and the
# report then holds the IRLS section only. PEERS_ONLY=where_users_wait
# runs step 7 alone and replaces only its section of results/performance.md.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
: "${BRDF_DATA:?set BRDF_DATA to the measured data folder}"
venv="${PEERS_VENV:-$(dirname "$repo")/venv-peers}"
case "$(realpath -m "$venv")/" in
"$repo"/*)
	echo "run.sh: PEERS_VENV ($venv) must lie outside the repository" >&2
	exit 1
	;;
esac
target="${CARGO_TARGET_DIR:-$repo/target}"
# Threads of both sides: rayon (faer inside our solvers) and the BLAS under
# NumPy. One by default: the machine is shared, and on a busy machine faer's
# thread pool stalls at its barriers. PEERS_THREADS=default
# leaves every library its own default.
threads="${PEERS_THREADS:-1}"
if [ "$threads" != default ]; then
	export RAYON_NUM_THREADS="$threads" OPENBLAS_NUM_THREADS="$threads" OMP_NUM_THREADS="$threads" MKL_NUM_THREADS="$threads"
fi
out="${PEERS_OUT:-$target/peers}"
only="${PEERS_ONLY:-all}"
case "$only" in
all | irls | where_users_wait) ;;
*)
	echo "run.sh: PEERS_ONLY must be all, irls or where_users_wait, not $only" >&2
	exit 1
	;;
esac
mkdir -p "$out"
echo "$only" >"$out/only.txt"
cd "$repo"

if [ ! -x "$venv/bin/python" ]; then
	python3 -m venv "$venv"
fi
"$venv/bin/pip" install -q -r benches/peers/requirements.txt -r benches/peers/irls_requirements.txt
py="$venv/bin/python"

: >"$out/commands.txt"
uptime >"$out/load_before.txt"
echo "$threads" >"$out/threads.txt"
if [ "$only" = all ]; then
	{
		echo 'cargo build --release -p brdf-benches --bin peer_fits'
		echo 'peer_fits --out $PEERS_OUT'
		echo 'python benches/peers/peers.py $PEERS_OUT'
	} >>"$out/commands.txt"
	cargo build --release -p brdf-benches --bin peer_fits
	bin="$target/release/peer_fits"
	"$bin" --out "$out" | tee "$out/rust.log"
	"$py" benches/peers/peers.py "$out" | tee "$out/python.log"
fi

# The commands users wait for alone, spliced into the existing report.
if [ "$only" = where_users_wait ]; then
	PY="$py" benches/peers/where_users_wait.sh "$out"
	uptime >"$out/load_after.txt"
	"$py" benches/peers/report.py "$out" results/performance.md >"$out/performance.md"
	cp "$out/performance.md" results/performance.md
	exit 0
fi

# IRLS side by side: the Rust side writes the designs and times itself, then
# statsmodels reads the same files.
{
	echo 'cargo build --release -p brdf-benches --bin irls_peer'
	echo 'irls_peer --out $PEERS_OUT/irls'
	echo 'python benches/peers/irls_statsmodels.py $PEERS_OUT/irls/designs > $PEERS_OUT/irls/statsmodels.jsonl'
} >>"$out/commands.txt"
rm -rf "$out/irls"
cargo build --release -p brdf-benches --bin irls_peer
"$target/release/irls_peer" --out "$out/irls"
"$py" benches/peers/irls_statsmodels.py "$out/irls/designs" >"$out/irls/statsmodels.jsonl"
# Where the IRLS time goes on the tall design (perf, when usable).
if perf record -q -o "$out/irls/perf.data" -- true >/dev/null 2>&1; then
	echo 'perf record -F 199 -- irls_peer --curet none --min-seconds 0 --out $PEERS_OUT/irls/profile' >>"$out/commands.txt"
	perf record -q -F 199 -o "$out/irls/perf.data" -- "$target/release/irls_peer" --curet none \
		--min-seconds 0 --out "$out/irls/profile" >/dev/null 2>&1
	perf report -i "$out/irls/perf.data" --stdio --no-children --sort symbol \
		2>/dev/null | grep -v '^#' | grep -v '^$' >"$out/irls/profile.txt"
	rm -rf "$out/irls/profile" "$out/irls/perf.data"
fi

if [ "$only" = all ]; then
	# The automatic fits as `brdf fit` runs them (12 starts, projection,
	# polish): every Kurt model on CUReT sample 25, and RGB fits of an RGL
	# material, timed by fit_loop (wall and processor time per fit).
	echo 'cargo build --release -p brdf-benches --bin fit_loop' >>"$out/commands.txt"
	cargo build --release -p brdf-benches --bin fit_loop
	rm -f "$out/fit_loop.jsonl"
	for m in phong blinn-phong ward ward-duer lafortune ashikhmin-shirley cook-torrance; do
		echo "fit_loop \$BRDF_DATA/curet/abrdf.dat#25 $m --reps 30 --json" >>"$out/commands.txt"
		"$target/release/fit_loop" "$BRDF_DATA/curet/abrdf.dat#25" "$m" --reps 30 --json >>"$out/fit_loop.jsonl"
	done
	for m in ashikhmin-shirley cook-torrance lafortune ward blinn-phong; do
		echo "fit_loop \$BRDF_DATA/rgl/paper_white_rgb.bsdf $m --reps 3 --json" >>"$out/commands.txt"
		"$target/release/fit_loop" "$BRDF_DATA/rgl/paper_white_rgb.bsdf" "$m" --reps 3 --json >>"$out/fit_loop.jsonl"
	done

	# The evaluation kernel of Ashikhmin-Shirley (criterion, one thread):
	# value and value + derivatives over precomputed geometry.
	echo "cargo bench -p brdf-benches --bench models -- 'kernels/ashikhmin-shirley/' --warm-up-time 2 --measurement-time 5" >>"$out/commands.txt"
	rm -rf "$target"/criterion/kernels/ashikhmin-shirley_* "$out/kernels"
	cargo bench -p brdf-benches --bench models -- 'kernels/ashikhmin-shirley/' --warm-up-time 2 --measurement-time 5 >"$out/kernels.log" 2>&1
	mkdir -p "$out/kernels"
	# criterion names the folders `ashikhmin-shirley_<path>`.
	for f in "$target"/criterion/kernels/ashikhmin-shirley_*/new; do
		name=$(basename "$(dirname "$f")")
		name=${name#ashikhmin-shirley_}
		cp "$f/estimates.json" "$out/kernels/$name.estimates.json"
		cp "$f/benchmark.json" "$out/kernels/$name.benchmark.json"
	done

	# Where the time goes: a flat profile (self time per function) of the two
	# Rust paths on the full-grid grey problem.
	rm -f "$out"/profile_*.txt
	profile_cmd=(--out "$out" --only paper_white_grey_as --no-export)
	if perf record -q -o "$out/perf.data" -- true >/dev/null 2>&1; then
		for s in bounded varpro; do
			echo "perf record -F 499 -- peer_fits --only paper_white_grey_as --no-export --solvers $s" >>"$out/commands.txt"
			perf record -q -F 499 -o "$out/perf_$s.data" -- "$bin" "${profile_cmd[@]}" --solvers "$s" >/dev/null 2>&1
			perf report -i "$out/perf_$s.data" --stdio --no-children --sort symbol \
				2>/dev/null | grep -v '^#' | grep -v '^$' >"$out/profile_$s.txt"
			/usr/bin/time -f "%e s elapsed, %U s user, %S s system, %F major + %R minor page faults, %M KiB max RSS" \
				-o "$out/time_$s.txt" "$bin" "${profile_cmd[@]}" --solvers "$s" >/dev/null
		done
		echo perf >"$out/profiler.txt"
	else
		for s in bounded varpro; do
			echo "valgrind --tool=callgrind -- peer_fits --only curet25_as --no-export --solvers $s" >>"$out/commands.txt"
			valgrind --tool=callgrind --callgrind-out-file="$out/callgrind_$s.out" \
				"$bin" --out "$out" --only curet25_as --no-export --solvers "$s" >/dev/null 2>&1
			callgrind_annotate "$out/callgrind_$s.out" 2>/dev/null | head -40 >"$out/profile_$s.txt"
		done
		echo callgrind >"$out/profiler.txt"
	fi
	# Optional: the full-grid grey bounded fit with the libraries' default
	# thread counts, against the same fit on one thread (minutes on a busy
	# machine).
	rm -f "$out/thread_check.txt"
	if [ "${PEERS_THREAD_CHECK:-0}" = 1 ]; then
		echo "peer_fits --only paper_white_grey_as --no-export --solvers bounded   # RAYON_NUM_THREADS=1, then unset" >>"$out/commands.txt"
		for t in 1 default; do
			if [ "$t" = 1 ]; then
				line=$(RAYON_NUM_THREADS=1 "$bin" --out "$out" --only paper_white_grey_as --no-export --solvers bounded | tail -1)
			else
				line=$(env -u RAYON_NUM_THREADS "$bin" --out "$out" --only paper_white_grey_as --no-export --solvers bounded | tail -1)
			fi
			echo "rayon threads $t: $line" >>"$out/thread_check.txt"
		done
	fi
	# Where users wait: default fits, select, batch, renderer kernels.
	PY="$py" benches/peers/where_users_wait.sh "$out"
fi
uptime >"$out/load_after.txt"

echo 'python benches/peers/report.py $PEERS_OUT > results/performance.md' >>"$out/commands.txt"
"$py" benches/peers/report.py "$out" >results/performance.md
echo "wrote results/performance.md"
