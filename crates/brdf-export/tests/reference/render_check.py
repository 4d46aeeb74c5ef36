"""Checks by rendering: every export of paper_white/ rendered in its renderer
beside brdf-render's render of the model the file holds, by HDR-FLIP
(flip-evaluator, brdf-render's noise-free render as the reference). Prints
the answers as JSON (paper_white/render_check.json); the Rust test
tests/render_check.rs asserts the bounds.

  python render_check.py EXR_DIR [--lights studio[,sky]] [--spp N] FILE...

FILE is an export; what renders it:
  M.xml        Mitsuba 3 (scalar_rgb): the paste-in snippet put on the sphere
               of the judge scene (benches/judge/scene.py), per light set
  M.scene.xml  Mitsuba 3: the complete scene, loaded with mi.load_file as
               `mitsuba scene.xml` does (its own light: studio)
  M.py, M.usda, M.gltf
               Blender Cycles: the EXRs cycles_render.py wrote in EXR_DIR
               (the script's material; the .usda through Blender's USD
               importer, the .gltf through its glTF importer), studio light
EXR_DIR also holds brdf-render's renders (examples/judge_exr.rs):
EXR_DIR/brdf-render/MODEL/LIGHT.exr for MODEL = M and M.KIND (the saved
models M.json, M.KIND.json). The model a file holds is M.KIND.json where
the export was converted (KIND: mitsuba, scene, blender, usd, gltf), else
M.json.

Per file and light: flip_held (the renderer against brdf-render of the model
the file holds: the export is exact, or mapped, when this is at the noise
floor), flip_source (against brdf-render of the fitted model M.json: for a
conversion, to set beside the image error the conversion printed) and
flip_reseeded (the renderer against itself at another seed: the noise
floor). Needs mitsuba, numpy, flip-evaluator.
"""

import json
import os
import sys

import flip_evaluator as flip
import mitsuba as mi
import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "..", "benches", "judge"))
import scene as S  # noqa: E402

SEEDS = (2, 3)


def read_exr(path):
    return np.array(mi.Bitmap(path), dtype=np.float32)[:, :, :3]


def hdr_flip(reference, test):
    return float(flip.evaluate(reference, test, "HDR")[1])


def kind_of(path):
    """(model stem M, export kind, renderer) of an export file."""
    base = os.path.basename(path)
    stem = base.split(".")[0]
    if base.endswith(".scene.xml"):
        return stem, "scene", "mitsuba"
    if base.endswith(".xml"):
        return stem, "mitsuba", "mitsuba"
    if base.endswith(".py"):
        return stem, "blender", "cycles"
    if base.endswith(".usda"):
        return stem, "usd", "cycles"
    if base.endswith(".gltf"):
        return stem, "gltf", "cycles"
    raise ValueError(f"{path}: no renderer checks this kind of export here")


def mitsuba_renders(path, kind, light, spp):
    """Two renders (seeds 2, 3) of the export in Mitsuba under `light`."""
    if kind == "scene":
        if light != "studio":
            return None
        scene = mi.load_file(path)
        return [np.array(mi.render(scene, spp=spp, seed=s), dtype=np.float32)[:, :, :3] for s in SEEDS]
    bsdf = S.bsdf_of(path)
    return [S.render(bsdf, light, seed=s, spp=spp) for s in SEEDS]


def main():
    args = sys.argv[1:]
    lights, spp = ["studio"], S.SPP
    if "--lights" in args:
        i = args.index("--lights")
        lights = args[i + 1].split(",")
        del args[i:i + 2]
    if "--spp" in args:
        i = args.index("--spp")
        spp = int(args[i + 1])
        del args[i:i + 2]
    exr_dir, files = args[0], args[1:]
    S.set_variant("scalar_rgb")
    out = {"mitsuba": mi.__version__, "flip_evaluator": getattr(flip, "__version__", "1.7"),
           "reference": "brdf-render (examples/judge_exr.rs), pixel centres, 128 px",
           "mitsuba_spp": spp, "checks": []}
    cycles_json = os.path.join(exr_dir, "cycles.json")
    cycles = None
    if os.path.exists(cycles_json):
        with open(cycles_json) as fh:
            cycles = json.load(fh)
        out["cycles"] = {k: cycles[k] for k in ("blender", "spp", "size", "light", "pixel_filter_width",
                                                "max_bounces", "view_transform", "units")}
    for f in files:
        stem, kind, renderer = kind_of(f)
        d = os.path.dirname(f)
        converted = os.path.exists(os.path.join(d, f"{stem}.{kind}.json"))
        held = f"{stem}.{kind}" if converted else stem
        check = {"file": os.path.relpath(f, here), "text": open(f).read(), "renderer": renderer,
                 "model": os.path.join(os.path.relpath(d, here), f"{held}.json"),
                 "source": os.path.join(os.path.relpath(d, here), f"{stem}.json"),
                 "converted": converted, "lights": {}}
        if renderer == "mitsuba":
            check["route"] = ("mi.load_file of the scene" if kind == "scene"
                              else "snippet on the sphere of the judge scene (benches/judge/scene.py)")
        else:
            if cycles is None:
                continue
            entries = {c["file"]: c for c in cycles["files"]}
            names = [n for n in entries if os.path.abspath(n) == os.path.abspath(f)]
            if not names:
                continue
            c = entries[names[0]]
            check["route"] = "Blender Cycles, " + c["route"]
            check["blender_material"] = {k: c.get(k) for k in ("material", "distribution", "inputs")}
        for light in lights:
            ours = os.path.join(exr_dir, "brdf-render", held, f"{light}.exr")
            source = os.path.join(exr_dir, "brdf-render", stem, f"{light}.exr")
            if renderer == "mitsuba":
                renders = mitsuba_renders(f, kind, light, spp)
                if renders is None:
                    continue
            else:
                if light != cycles["light"]:
                    continue
                base = os.path.join(exr_dir, os.path.relpath(f).replace("/", "."))
                renders = [read_exr(f"{base}.{light}.seed{s}.exr") for s in SEEDS]
            held_img, source_img = read_exr(ours), read_exr(source)
            check["lights"][light] = {
                "flip_held": hdr_flip(held_img, renders[0]),
                "flip_source": hdr_flip(source_img, renders[0]),
                "flip_reseeded": hdr_flip(renders[0], renders[1]),
                "flip_brdf_render_held_vs_source": hdr_flip(source_img, held_img),
                "brdf_render_mean": [float(x) for x in held_img.reshape(-1, 3).mean(axis=0, dtype=np.float64)],
                "renderer_mean": [float(x) for x in renders[0].reshape(-1, 3).mean(axis=0, dtype=np.float64)],
            }
        out["checks"].append(check)
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
