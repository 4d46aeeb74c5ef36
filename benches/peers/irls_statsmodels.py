"""Times statsmodels RLM (Tukey bisquare c = 4.685, scale_est='mad', its
default deviance test) on the designs the Rust IRLS bench writes
(benches/benches/irls.rs: manifest.json plus row-major little-endian f64
files, the response in the last column), and prints one JSON object per
design: {name, rows, cols, iterations, seconds, coefficients}.

    python3 irls_statsmodels.py DIR [NAME ...] [--repeat N]

DIR is where the bench wrote the designs ($BRDF_IRLS_EXPORT, default
irls-designs under cargo's target tmp directory). `seconds` is the best of
N timed fits (default 5). `iterations` is statsmodels' own count
(fit_history['iteration'], which includes the least-squares start)."""
import argparse
import json
import time
from pathlib import Path

import numpy as np
import statsmodels.api as sm
from statsmodels.robust import norms


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("names", nargs="*")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    root = Path(args.dir)
    manifest = json.loads((root / "manifest.json").read_text())
    for d in manifest["designs"]:
        if args.names and d["name"] not in args.names:
            continue
        a = np.fromfile(root / d["file"], dtype="<f8").reshape(d["rows"], d["cols"] + 1)
        X, y = np.ascontiguousarray(a[:, :-1]), a[:, -1].copy()
        best, res = float("inf"), None
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            res = sm.RLM(y, X, M=norms.TukeyBiweight(c=4.685)).fit(scale_est="mad")
            best = min(best, time.perf_counter() - t0)
        print(json.dumps({
            "name": d["name"], "rows": d["rows"], "cols": d["cols"],
            "iterations": int(res.fit_history["iteration"]),
            "seconds": best,
            "coefficients": res.params.tolist(),
        }))


if __name__ == "__main__":
    main()
