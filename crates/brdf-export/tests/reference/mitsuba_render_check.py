"""Render an exported Mitsuba BSDF in Mitsuba's judge scene
(benches/judge/scene.py: 128 px, 256 spp, seed 2) under both light sets and
compare with brdf-render's render of the same saved model
(examples/judge_exr.rs) by HDR-FLIP (flip-evaluator), Mitsuba as the
reference. Prints the FLIP per light set as JSON.

  cargo run --release -p brdf-export --example judge_exr -- paper_white/principled.json /tmp/jr
  python mitsuba_render_check.py paper_white/principled.xml /tmp/jr > paper_white/render_check.json
Needs mitsuba, numpy, flip-evaluator."""

import json
import os
import sys

import flip_evaluator as flip
import mitsuba as mi
import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "..", "benches", "judge"))
import scene as S  # noqa: E402

from mitsuba_check import load_bsdf  # noqa: E402


def main():
    xml_file, exr_dir = sys.argv[1], sys.argv[2]
    S.set_variant("scalar_rgb")
    bsdf = load_bsdf(open(xml_file).read())
    out = {"file": os.path.relpath(xml_file, here), "mitsuba": mi.__version__, "lights": {}}
    for light in S.LIGHTS:
        ref = S.render(bsdf, light, seed=2)
        ours = np.array(mi.Bitmap(os.path.join(exr_dir, f"{light}.exr")), dtype=np.float32)[:, :, :3]
        # Also the noise floor: Mitsuba against itself at another seed.
        again = S.render(bsdf, light, seed=3)
        f = flip.evaluate(ref, ours, "HDR")[1]
        floor = flip.evaluate(ref, again, "HDR")[1]
        out["lights"][light] = {"flip_brdf_render": float(f), "flip_mitsuba_reseeded": float(floor)}
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
