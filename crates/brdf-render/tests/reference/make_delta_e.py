"""The judge's mean-colour CIEDE2000 (benches/judge/metrics.py: both mean
colours scaled so the reference's luminance is 0.5, linear sRGB -> XYZ ->
CIELAB D65, colour-science's CIE 2000) on fixed colour pairs, written to
delta_e_judge.json for crates/brdf-render/tests/judge.rs.

    python make_delta_e.py > delta_e_judge.json   (colour-science 0.4.6)
"""

import json

import colour
import numpy as np

PAIRS = [
    # a dark film body and a browner fit (the issue-23 case), both at the
    # brightness of a 1 / p99-exposed glossy render
    ([0.031, 0.012, 0.018], [0.036, 0.014, 0.011]),
    # a matte red paint and a slightly darker fit
    ([0.0739, 0.0166, 0.0167], [0.0752, 0.0170, 0.0172]),
    # grey against a bluish grey, in absolute radiance units
    ([2.0, 2.0, 2.0], [1.8, 1.9, 2.3]),
    # a negative channel clipped, as the judge clips mean colours
    ([0.2, 0.05, -0.01], [0.19, 0.06, 0.02]),
]


def delta_e(a, b):
    a, b = np.maximum(np.array(a), 0.0), np.maximum(np.array(b), 0.0)
    s = 0.5 / float(colour.sRGB_to_XYZ(a, apply_cctf_decoding=False)[1])
    lab = [colour.XYZ_to_Lab(colour.sRGB_to_XYZ(c * s, apply_cctf_decoding=False)) for c in (a, b)]
    return float(colour.delta_E(lab[0], lab[1], method="CIE 2000"))


print(json.dumps([{"reference": a, "test": b, "delta_e": delta_e(a, b)} for a, b in PAIRS], indent=1))
