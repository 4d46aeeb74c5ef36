"""Times statsmodels RLM (Tukey bisquare c = 4.685, scale_est='mad', its
default deviance test, tol 1e-8, maxiter 50) on the designs written by
`irls_peer` (benches/src/bin/irls_peer.rs) or the IRLS bench
(benches/benches/irls.rs): manifest.json plus row-major little-endian f64
files, the response in the last column. Prints one JSON object per design:
{name, rows, cols, iterations, wls_solves, converged, seconds, runs,
coefficients, versions}.

    python3 irls_statsmodels.py DIR [NAME ...] [--repeat N] [--min-seconds S]

DIR is the designs folder ($PEERS_OUT/irls/designs in benches/peers/run.sh).
Each fit runs at least N times (default 3) and until about S seconds
(default 0.2) have passed, at most 1000 times; `seconds` is the median wall
time of one fit, as `irls_peer` times the Rust side. `iterations` is
statsmodels' own count (fit_history['iteration'], which counts the
least-squares start), `wls_solves` = iterations - 1 the reweighted solves
after it (what the Rust side calls iterations). `converged`: the last
deviance change is within tol (statsmodels stops at maxiter without saying
so)."""
import argparse
import json
import time
from pathlib import Path

import platform

import numpy as np
import statsmodels
import statsmodels.api as sm
from statsmodels.robust import norms

TOL, MAXITER = 1e-8, 50


def fit(X, y):
    return sm.RLM(y, X, M=norms.TukeyBiweight(c=4.685)).fit(
        scale_est="mad", conv="dev", tol=TOL, maxiter=MAXITER
    )


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("names", nargs="*")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--min-seconds", type=float, default=0.2)
    args = ap.parse_args()
    root = Path(args.dir)
    manifest = json.loads((root / "manifest.json").read_text())
    for d in manifest["designs"]:
        if args.names and d["name"] not in args.names:
            continue
        a = np.fromfile(root / d["file"], dtype="<f8").reshape(d["rows"], d["cols"] + 1)
        X, y = np.ascontiguousarray(a[:, :-1]), a[:, -1].copy()
        times, res = [], None
        while len(times) < max(args.repeat, 1) or sum(times) < args.min_seconds:
            t0 = time.perf_counter()
            res = fit(X, y)
            times.append(time.perf_counter() - t0)
            if len(times) >= 1000:
                break
        dev = res.fit_history["deviance"]
        print(json.dumps({
            "name": d["name"], "rows": d["rows"], "cols": d["cols"],
            "iterations": int(res.fit_history["iteration"]),
            "wls_solves": int(res.fit_history["iteration"]) - 1,
            "converged": bool(abs(dev[-1] - dev[-2]) <= TOL),
            "seconds": float(np.median(times)),
            "runs": len(times),
            "coefficients": res.params.tolist(),
            "versions": {"python": platform.python_version(), "numpy": np.__version__,
                         "statsmodels": statsmodels.__version__},
        }), flush=True)


if __name__ == "__main__":
    main()
