"""Evaluate every exported Mitsuba BSDF in Mitsuba 3 itself (variant
scalar_rgb) at fixed direction pairs and store f = value / cos(theta_o),
and at the normal (wi = wo = n) as "peak".

The pairs are a quasi-random (Kronecker) sequence over the hemisphere up
to 85 deg, uniform in cos(theta) and in phi; their components are rounded
to single precision here, so Mitsuba (which computes in single precision)
and the Rust test (double) evaluate at exactly the same directions.

Run (venv with `pip install mitsuba numpy`; check_exports.sh does):
  cargo run -p brdf-export --example mitsuba_cases > mitsuba_cases.json
  python mitsuba_check.py mitsuba_cases.json > mitsuba_values.json
Any JSON list of objects with an "xml" member works (paper_white/).
"""

import json
import math
import re
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")


def sph(t, p):
    return [math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)]


def f32(v):
    return [float(np.float32(x)) for x in v]


def pairs(n):
    # Roberts' R4 sequence: steps 1/g^k, g the root of x^5 = x + 1.
    g = 1.1673039782614187
    steps = [g ** -(k + 1) for k in range(4)]
    out = []
    for i in range(n):
        u = [(0.5 + i * a) % 1.0 for a in steps]
        ti, to = math.acos(1 - u[0] * (1 - math.cos(1.48))), math.acos(1 - u[1] * (1 - math.cos(1.48)))
        out.append((f32(sph(ti, 2 * math.pi * u[2])), f32(sph(to, 2 * math.pi * u[3]))))
    return out


def load_bsdf(xml):
    """The BSDF of an export: a `<bsdf id=...>` snippet (no version: it is
    pasted into a scene) is wrapped in a scene with a sphere referencing it,
    as a user pastes it; a complete scene is loaded as is. Returns the
    sphere's BSDF (the one shape that is not an emitter)."""
    if "<scene" not in xml:
        bid = re.search(r'<bsdf[^>]*\bid="([^"]+)"', xml).group(1)
        xml = (f'<scene version="3.0.0">{xml}'
               f'<shape type="sphere"><ref id="{bid}"/></shape></scene>')
    scene = mi.load_string(xml)
    return [s for s in scene.shapes() if not s.is_emitter()][0].bsdf()


def main():
    cases = json.load(open(sys.argv[1]))
    ps = pairs(300)
    for c in cases:
        bsdf = load_bsdf(c["xml"])
        ctx = mi.BSDFContext()
        si = mi.SurfaceInteraction3f()
        si.n = mi.Normal3f(0, 0, 1)
        si.sh_frame = mi.Frame3f(mi.Vector3f(1, 0, 0), mi.Vector3f(0, 1, 0), mi.Vector3f(0, 0, 1))
        def f(wi, wo):
            si.wi = mi.Vector3f(*wi)
            v = bsdf.eval(ctx, si, mi.Vector3f(*wo))
            return [float(v[k]) / wo[2] for k in range(3)]

        c["pairs"] = ps
        c["values"] = [f(wi, wo) for wi, wo in ps]
        c["peak"] = f([0.0, 0.0, 1.0], [0.0, 0.0, 1.0])
    print(json.dumps({"mitsuba": mi.__version__, "cases": cases}))


if __name__ == "__main__":
    main()
