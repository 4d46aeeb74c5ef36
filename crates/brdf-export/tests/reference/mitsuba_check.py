"""Evaluate every exported Mitsuba BSDF in Mitsuba 3 itself (variant
scalar_rgb) at fixed direction pairs and store f = value / cos(theta_o).

Run (venv with `pip install mitsuba numpy`):
  cargo run -p brdf-export --example mitsuba_cases > mitsuba_cases.json
  python mitsuba_check.py mitsuba_cases.json > mitsuba_values.json
"""

import json
import math
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")


def sph(t, p):
    return [math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)]


def pairs(n):
    # Deterministic pairs above the horizon, up to 85 deg.
    out = []
    for i in range(n):
        u = [((i * a) % 1000) / 1000.0 for a in (0.6180339887, 0.7548776662, 0.5698402910, 0.8191725133)]
        ti, to = math.acos(1 - u[0] * (1 - math.cos(1.48))), math.acos(1 - u[1] * (1 - math.cos(1.48)))
        out.append((sph(ti, 2 * math.pi * u[2]), sph(to, 2 * math.pi * u[3])))
    return out


def main():
    cases = json.load(open(sys.argv[1]))
    ps = pairs(300)
    for c in cases:
        bsdf = mi.load_string(c["xml"])
        ctx = mi.BSDFContext()
        si = mi.SurfaceInteraction3f()
        si.n = mi.Normal3f(0, 0, 1)
        si.sh_frame = mi.Frame3f(mi.Vector3f(1, 0, 0), mi.Vector3f(0, 1, 0), mi.Vector3f(0, 0, 1))
        vals = []
        for wi, wo in ps:
            si.wi = mi.Vector3f(*wi)
            v = bsdf.eval(ctx, si, mi.Vector3f(*wo))
            vals.append([float(v[k]) / wo[2] for k in range(3)])
        c["pairs"] = ps
        c["values"] = vals
    print(json.dumps(cases))


if __name__ == "__main__":
    main()
