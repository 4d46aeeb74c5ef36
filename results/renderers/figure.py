"""The renderer figure of README.md and docs/export.md: a measured material
rendered by Mitsuba 3's `measured` plugin (the judge's reference,
docs/appearance.md), its `brdf fit --for mitsuba` material rendered by
Mitsuba, its `brdf fit --for blender` material rendered by Blender Cycles
(cycles_render.py's EXR, Gaussian pixel filter) and its `brdf fit --for
materialx` document rendered by MaterialX's GLSL renderer
(materialx_render.py's EXR, brdf-render's film), in the judge scene under
the studio light. Writes four PNG tiles (one exposure, 1 / p99 of the
measurement, gamma 2.2) and renderers.md with the HDR-FLIP of each render
against the measurement (both clipped at 0, as the judge's). The models
chosen are read from the fits saved beside the materials
(MATERIAL.mitsuba.json, MATERIAL.blender.json, MATERIAL.materialx.json).

    python figure.py MATERIAL.bsdf FIT.xml CYCLES.exr MATERIALX.exr OUT_DIR
Needs mitsuba, numpy, flip-evaluator (run by make.sh)."""

import json
import os
import sys

import flip_evaluator as flip
import mitsuba as mi
import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "benches", "judge"))
import scene as S  # noqa: E402


def png(img, exposure, path):
    ldr = np.clip(np.maximum(img, 0.0) * exposure, 0.0, 1.0) ** (1.0 / 2.2)
    out = np.ascontiguousarray((ldr * 255.0 + 0.5).astype(np.uint8))
    mi.Bitmap(out, pixel_format=mi.Bitmap.PixelFormat.RGB).write(path)


def main():
    measured, xml, exr, mx_exr, out = sys.argv[1:6]
    S.set_variant("scalar_rgb")
    name = os.path.basename(measured).removesuffix(".bsdf")
    ref = S.render(S.bsdf_of(measured), "studio", seed=1)
    mitsuba = S.render(S.bsdf_of(xml), "studio", seed=2)
    cycles = np.array(mi.Bitmap(exr), dtype=np.float32)[:, :, :3]
    materialx = np.array(mi.Bitmap(mx_exr), dtype=np.float32)[:, :, :3]
    ref, mitsuba, cycles, materialx = (np.ascontiguousarray(np.maximum(i, 0.0), dtype=np.float32)
                                       for i in (ref, mitsuba, cycles, materialx))
    exposure = 1.0 / float(np.percentile(ref, 99))
    tiles = {"measured": ref, "mitsuba": mitsuba, "cycles": cycles, "materialx": materialx}
    chosen = {k: label(json.load(open(os.path.join(out, f"{name}.{k}.json"))))
              for k in ("mitsuba", "blender", "materialx")}
    for k, img in tiles.items():
        png(img, exposure, os.path.join(out, f"{name}.{k}.studio.png"))
    f = {k: float(flip.evaluate(ref, tiles[k], "HDR")[1]) for k in ("mitsuba", "cycles", "materialx")}
    md = f"""| measurement (Mitsuba `measured`) | Mitsuba 3: `brdf fit --for mitsuba` | Blender Cycles: `brdf fit --for blender` | MaterialX GLSL: `brdf fit --for materialx` |
| --- | --- | --- | --- |
| ![measured](results/renderers/{name}.measured.studio.png) | ![Mitsuba](results/renderers/{name}.mitsuba.studio.png) | ![Blender](results/renderers/{name}.cycles.studio.png) | ![MaterialX](results/renderers/{name}.materialx.studio.png) |
| `rgl/{name}.bsdf` | `{chosen['mitsuba']}`: HDR-FLIP {f['mitsuba']:.3f} | `{chosen['blender']}`: HDR-FLIP {f['cycles']:.3f} | `{chosen['materialx']}`: HDR-FLIP {f['materialx']:.3f} |
"""
    with open(os.path.join(out, "renderers.md"), "w") as fh:
        fh.write(md)
    json.dump({"material": name, "light": "studio", "exposure": exposure, "flip_vs_measured": f,
               "models": chosen,
               "mitsuba": mi.__version__}, open(os.path.join(out, "renderers.json"), "w"), indent=1)
    print(md)


def label(saved):
    """A saved model's name, with its lobe count where it is not one (as
    `brdf fit --for` names its choice)."""
    lobes = saved.get("structure", {}).get("lobes", 1)
    return saved["model"] + (f" ({lobes} lobes)" if lobes != 1 else "")


if __name__ == "__main__":
    main()
