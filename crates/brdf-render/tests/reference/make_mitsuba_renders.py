"""Mitsuba's answers for brdf-render's judge scene (tests/mitsuba_sky.rs).

Renders, in the judge scene of `docs/appearance.md` (the functions of
`benches/judge/scene.py`: Mitsuba 3.9.1 `scalar_rgb`, unit sphere, camera at
(0, 0, 6), 22 deg, 128 x 128 px), BSDFs whose formulas the Rust test
reproduces exactly:

- `lambert`: `diffuse`, reflectance (0.8, 0.6, 0.4);
- `glossy`, `sharp`: `blendbsdf` of `diffuse` (0.2, 0.4, 0.7) and a
  `roughconductor` (GGX, separable Smith shadowing, `material = none`, i.e.
  Fresnel 1) of alpha 0.15 and 0.05, weight 0.3 on the conductor.

Each case under each light set is written as `CASE.LIGHT.exr` (linear RGB,
float32) at `SPP` samples per pixel (seed 1), more than the judge's 256 so
that the committed answer is closer to the noise-free image brdf-render
computes. `mitsuba_renders.json` records the cases, the Mitsuba version and
the noise of these references: the HDR-FLIP of the reference against the
same render at seed 2, and against a judge-like 256-spp render.

    python crates/brdf-render/tests/reference/make_mitsuba_renders.py
"""

import json
import sys
from pathlib import Path

import flip_evaluator
import mitsuba as mi
import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[3] / "benches" / "judge"))
import scene as S  # noqa: E402

SPP = 1024
SIZE = 128


def blend(alpha):
    return {
        "type": "blendbsdf",
        "weight": 0.3,
        "diffuse": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.2, 0.4, 0.7]}},
        "conductor": {
            "type": "roughconductor",
            "distribution": "ggx",
            "alpha": alpha,
            "material": "none",
        },
    }


CASES = {
    "lambert": (
        {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.8, 0.6, 0.4]}},
        {"kd": [0.8, 0.6, 0.4], "spec_weight": 0.0, "alpha": 0.0},
    ),
    "glossy": (blend(0.15), {"kd": [0.2, 0.4, 0.7], "spec_weight": 0.3, "alpha": 0.15}),
    "sharp": (blend(0.05), {"kd": [0.2, 0.4, 0.7], "spec_weight": 0.3, "alpha": 0.05}),
}
RUNS = [("lambert", "sky"), ("glossy", "sky"), ("sharp", "sky"), ("glossy", "studio")]


def flip(a, b):
    return float(flip_evaluator.evaluate(a, b, "HDR")[1])


def main():
    S.set_variant("scalar_rgb")
    meta = {"mitsuba": mi.__version__, "size": SIZE, "spp": SPP, "seed": 1, "renders": []}
    for case, light in RUNS:
        bsdf, params = CASES[case]
        ref = S.render(mi.load_dict(bsdf), light, seed=1, size=SIZE, spp=SPP)
        again = S.render(mi.load_dict(bsdf), light, seed=2, size=SIZE, spp=SPP)
        judge = S.render(mi.load_dict(bsdf), light, seed=2, size=SIZE, spp=256)
        name = f"{case}.{light}.exr"
        mi.Bitmap(np.ascontiguousarray(ref), pixel_format=mi.Bitmap.PixelFormat.RGB).write(
            str(HERE / name)
        )
        row = {
            "file": name,
            "case": case,
            "light": light,
            "params": params,
            "flip_reseeded": flip(ref, again),
            "flip_256spp": flip(ref, judge),
        }
        print(row, file=sys.stderr)
        meta["renders"].append(row)
    (HERE / "mitsuba_renders.json").write_text(json.dumps(meta, indent=1) + "\n")


if __name__ == "__main__":
    main()
