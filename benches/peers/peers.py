"""SciPy's least_squares on the peer problems exported by `peer_fits`.

For every problem folder under DIR (written by `peer_fits`, see
benches/src/peers/export.rs):

1. checks this file's NumPy Ashikhmin-Shirley model (written from the
   formula, independently of the Rust code) against the Rust model values
   and residual Jacobian at the start, to 1e-10 relative;
2. fits with `least_squares(method="trf")` inside the same box with the
   analytic Jacobian (SciPy's default tolerances, and tight ones), and with
   `method="lm"` unbounded (flagged when it leaves the box), all from the
   exported start;
3. evaluates ONE cost function, 0.5 * sum of squared rows
   `s_j (M_cj(p) - y_cj)`, at the final parameters of every solver, the
   Rust ones included, and writes `python_results.json` beside the export.

Usage: python peers.py DIR [--only NAME[,NAME..]]
"""

import json
import sys
import time
from pathlib import Path

import numpy as np
import scipy
from scipy.optimize import least_squares

CHECK_RTOL = 1e-10


class AshikhminShirley:
    """Isotropic Ashikhmin-Shirley with Lambert diffuse, `nc` channels.

    f_c = kd_c / pi + ks_c S,
    S = (n + 1) / (8 pi) (N.H)^n F(V.H) / ((V.H) max(N.L, N.V)),
    F(c) = f0 + (1 - f0) (1 - c)^5.
    Parameters: kd_0..kd_{nc-1}, ks_0..ks_{nc-1}, n, f0.
    Derivatives: dS/dn = S / (n + 1) + S ln(N.H); dS/df0 = S0 (1 - (1 - V.H)^5)
    with S0 the lobe without the Fresnel factor.
    """

    def __init__(self, L, V, nc):
        self.nc = nc
        h = L + V
        h /= np.linalg.norm(h, axis=1)[:, None]
        nh = np.clip(h[:, 2], -1.0, 1.0)
        self.pos = nh > 0.0
        self.ln_nh = np.where(self.pos, np.log(np.minimum(np.where(self.pos, nh, 1.0), 1.0)), 0.0)
        vh = np.einsum("ij,ij->i", V, h)
        self.vh = vh
        self.max_cos = np.maximum(L[:, 2], V[:, 2])
        m = 1.0 - np.clip(vh, 0.0, 1.0)
        self.m5 = m**5

    def lobe(self, n, f0):
        """S, the lobe without Fresnel, and the Fresnel factor."""
        pw = np.where(self.pos, np.exp(n * self.ln_nh), 0.0)
        s0 = (n + 1.0) / (8.0 * np.pi) * pw / (self.vh * self.max_cos)
        fr = f0 + (1.0 - f0) * self.m5
        return s0 * fr, s0, fr

    def values(self, p):
        nc = self.nc
        s, _, _ = self.lobe(p[2 * nc], p[2 * nc + 1])
        return np.stack([p[c] / np.pi + p[nc + c] * s for c in range(nc)])

    def jacobian(self, p, scales):
        """Jacobian of the rows s_j (f_c - y_c), row c * n + j."""
        nc = self.nc
        n_exp = p[2 * nc]
        s, s0, _ = self.lobe(n_exp, p[2 * nc + 1])
        ds_dn = s / (n_exp + 1.0) + s * self.ln_nh
        ds_df0 = s0 * (1.0 - self.m5)
        m = s.size
        jac = np.zeros((nc * m, 2 * nc + 2))
        for c in range(nc):
            rows = slice(c * m, (c + 1) * m)
            ks = p[nc + c]
            jac[rows, c] = scales / np.pi
            jac[rows, nc + c] = scales * s
            jac[rows, 2 * nc] = scales * ks * ds_dn
            jac[rows, 2 * nc + 1] = scales * ks * ds_df0
        return jac


MODELS = {"ashikhmin-shirley": AshikhminShirley}


class Problem:
    def __init__(self, folder):
        self.folder = folder
        self.meta = json.loads((folder / "meta.json").read_text())
        self.L = np.load(folder / "L.npy")
        self.V = np.load(folder / "V.npy")
        self.values = np.load(folder / "values.npy")
        self.scales = np.load(folder / "scales.npy")
        self.nc = self.meta["channels"]
        self.model = MODELS[self.meta["model"]](self.L, self.V, self.nc)
        self.targets = (self.values * self.scales[None, :]).ravel()
        self.start = np.array(self.meta["start"])
        self.lower = np.array(self.meta["lower"])
        self.upper = np.array(self.meta["upper"])

    def rows(self, p):
        return (self.model.values(p) * self.scales[None, :]).ravel() - self.targets

    def jac(self, p):
        return self.model.jacobian(p, self.scales)

    def cost(self, p):
        """The one shared cost: 0.5 * sum over channels and samples of
        (s_j (M_cj(p) - y_cj))^2."""
        p = np.asarray(p, dtype=float)
        if not np.all(np.isfinite(p)):
            return float("nan")
        r = self.scales[None, :] * (self.model.values(p) - self.values)
        return 0.5 * float(np.sum(r * r))

    def inside(self, p):
        tol = 1e-12 * np.maximum(np.abs(self.upper - self.lower), 1.0)
        return bool(np.all(p >= self.lower - tol) and np.all(p <= self.upper + tol))


def rel_err(a, b):
    """Largest |a - b| / |b| with |b| floored at 1e-12 of the largest |b| of its column."""
    a = a.reshape(a.shape[0], -1)
    b = b.reshape(b.shape[0], -1)
    floor = np.maximum(1e-12 * np.max(np.abs(b), axis=0, keepdims=True), 1e-300)
    return float(np.max(np.abs(a - b) / np.maximum(np.abs(b), floor)))


def check(prob):
    out = {}
    rust = np.load(prob.folder / "model_at_start.npy")
    out["model_rel_err"] = rel_err(prob.model.values(prob.start).T, rust.T)
    jf = prob.folder / "jacobian_at_start.npy"
    if jf.exists():
        out["jacobian_rel_err"] = rel_err(prob.jac(prob.start), np.load(jf))
    out["cost_at_start_python"] = prob.cost(prob.start)
    out["cost_at_start_rust"] = prob.meta["rust_cost_at_start"]
    bad = [k for k in ("model_rel_err", "jacobian_rel_err") if out.get(k, 0.0) > CHECK_RTOL]
    if bad:
        raise SystemExit(f"{prob.folder.name}: NumPy model disagrees with Rust: {out}")
    return out


def timed(f):
    """Median wall time of f() and mean processor time (whole process, all
    threads); repeated until about a second passes when one run is under
    0.2 s (the same rule as the Rust side)."""
    times = []
    cpu0 = time.process_time()
    while True:
        t0 = time.perf_counter()
        res = f()
        dt = time.perf_counter() - t0
        times.append(dt)
        if dt >= 0.2 or sum(times) >= 1.0 or len(times) >= 200:
            cpu = (time.process_time() - cpu0) / len(times)
            return float(np.median(times)), cpu, len(times), res


def scipy_fits(prob):
    runs = [
        ("scipy trf (box, default tol 1e-8)", dict(method="trf", bounds=(prob.lower, prob.upper))),
        (
            "scipy trf (box, tol 1e-12)",
            dict(method="trf", bounds=(prob.lower, prob.upper), ftol=1e-12, xtol=1e-12, gtol=1e-12),
        ),
        ("scipy lm (unbounded, default tol)", dict(method="lm")),
    ]
    out = []
    for name, kw in runs:
        seconds, cpu, repeats, res = timed(lambda: least_squares(prob.rows, prob.start, jac=prob.jac, **kw))
        out.append(
            {
                "solver": name,
                "params": res.x.tolist(),
                "seconds": seconds,
                "cpu_seconds": cpu,
                "repeats": repeats,
                "residual_evals": int(res.nfev),
                "jacobian_evals": None if res.njev is None else int(res.njev),
                "termination": f"status {res.status}: {res.message}",
                "inside_box": prob.inside(res.x),
                "own_cost": float(res.cost),
            }
        )
        print(f"  {name:<42} {seconds:9.4f} s (cpu {cpu:.4f} s)  x{repeats:<3} nfev {res.nfev:4} cost {res.cost:.10e}")
    return out


def main(argv):
    if len(argv) < 2:
        raise SystemExit(__doc__)
    root = Path(argv[1])
    only = None
    if len(argv) > 3 and argv[2] == "--only":
        only = set(argv[3].split(","))
    for folder in sorted(p.parent for p in root.glob("*/meta.json")):
        if only is not None and folder.name not in only:
            continue
        meta = json.loads((folder / "meta.json").read_text())
        if meta["model"] not in MODELS:
            print(f"{folder.name}: model {meta['model']} has no NumPy version here; skipped")
            continue
        prob = Problem(folder)
        print(f"{folder.name}: {meta['samples']} samples, {prob.nc} channels")
        checks = check(prob)
        print(f"  checks {checks}")
        fits = scipy_fits(prob)
        rust = json.loads((folder / "rust_results.json").read_text())
        for r in rust + fits:
            r["cost"] = prob.cost(np.array([np.nan if x is None else x for x in r["params"]]))
        result = {
            "numpy": np.__version__,
            "scipy": scipy.__version__,
            "python": sys.version.split()[0],
            "checks": checks,
            "rust": rust,
            "scipy_fits": fits,
        }
        (folder / "python_results.json").write_text(json.dumps(result, indent=1))


if __name__ == "__main__":
    main(sys.argv)
