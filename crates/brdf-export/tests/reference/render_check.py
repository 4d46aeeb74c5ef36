"""Checks by rendering: every export of paper_white/ rendered in its renderer
beside brdf-render's render of the model the file holds, by HDR-FLIP
(flip-evaluator, brdf-render's noise-free render as the reference). Prints
the answers as JSON (paper_white/render_check.json); the Rust test
tests/export/render_check.rs asserts the bounds.

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
  M.mtlx, M.openpbr.mtlx
               MaterialX's GLSL renderer: the EXRs materialx_render.py wrote
               in EXR_DIR (GLSL generated for the document's material),
               studio light; for a `gltf_pbr` document also its render with
               the glTF spec's formulas (materialx_gltf_spec.py):
               flip_held_gltf_spec
EXR_DIR also holds brdf-render's renders (examples/judge_exr.rs):
EXR_DIR/brdf-render/MODEL/LIGHT.exr for MODEL = M and M.KIND (the saved
models M.json, M.KIND.json). The model a file holds is M.KIND.json where
the export was converted (KIND: mitsuba, scene, blender, usd, gltf,
materialx, openpbr), else M.json.

Per file and light: flip_held (the renderer against brdf-render of the model
the file holds: the export is exact, or mapped, when this is at the noise
floor), flip_source (against brdf-render of the fitted model M.json: for a
conversion, to set beside the image error the conversion printed) and
flip_reseeded (the renderer against itself at another seed: the noise
floor; MaterialX's renderer has no seed: a rerun). Needs mitsuba, numpy,
flip-evaluator.
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
# Renderers that write EXRs and a report NAME.json into EXR_DIR for this script.
EXR_RENDERERS = ("cycles", "materialx")


def read_exr(path):
    return np.array(mi.Bitmap(path), dtype=np.float32)[:, :, :3]


def write_exr(path, img):
    """A linear RGB float EXR of the H x W x 3 array `img`."""
    mi.Bitmap(np.ascontiguousarray(img, dtype=np.float32), mi.Bitmap.PixelFormat.RGB).write(path)


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
    if base.endswith(".openpbr.mtlx"):
        return stem, "openpbr", "materialx"
    if base.endswith(".mtlx"):
        return stem, "materialx", "materialx"
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


def renderer_reports(exr_dir):
    """The reports the EXR-writing renderers left in EXR_DIR (cycles.json
    from cycles_render.py, materialx.json from materialx_render.py)."""
    reports = {}
    for renderer in EXR_RENDERERS:
        path = os.path.join(exr_dir, f"{renderer}.json")
        if os.path.exists(path):
            with open(path) as fh:
                reports[renderer] = json.load(fh)
    return reports


def settings_of(renderer, report):
    """What render_check.json keeps of a renderer's report: its settings."""
    if renderer == "cycles":
        return {k: report[k] for k in ("blender", "spp", "size", "light", "pixel_filter_width",
                                       "max_bounces", "view_transform", "units")}
    return {k: v for k, v in report.items() if k != "files"}


def describe(check, renderer, kind, entry):
    """The route a file took to its renderer and what the renderer made of it."""
    if renderer == "mitsuba":
        check["route"] = ("mi.load_file of the scene" if kind == "scene"
                          else "snippet on the sphere of the judge scene (benches/judge/scene.py)")
    elif renderer == "cycles":
        check["route"] = "Blender Cycles, " + entry["route"]
        check["blender_material"] = {k: entry.get(k) for k in ("material", "distribution", "inputs")}
    else:
        check["route"] = "MaterialX GlslRenderer (GLSL generated for the document's material)"
        check["materialx_material"] = {"material": entry["material"], "shader_node": entry["shader_node"]}


def entry_of(report, f):
    """The renderer report's entry for file `f`, if it rendered it."""
    names = [e for e in report["files"] if os.path.abspath(e["file"]) == os.path.abspath(f)]
    return names[0] if names else None


def compare(held_img, source_img, renders):
    """The HDR-FLIPs of a render against brdf-render's pictures and itself."""
    return {
        "flip_held": hdr_flip(held_img, renders[0]),
        "flip_source": hdr_flip(source_img, renders[0]),
        "flip_reseeded": hdr_flip(renders[0], renders[1]),
        "flip_brdf_render_held_vs_source": hdr_flip(source_img, held_img),
        "brdf_render_mean": [float(x) for x in held_img.reshape(-1, 3).mean(axis=0, dtype=np.float64)],
        "renderer_mean": [float(x) for x in renders[0].reshape(-1, 3).mean(axis=0, dtype=np.float64)],
    }


def check_file(f, exr_dir, lights, spp, reports):
    """The check of export `f`, or None when its renderer left no render."""
    stem, kind, renderer = kind_of(f)
    d = os.path.dirname(f)
    converted = os.path.exists(os.path.join(d, f"{stem}.{kind}.json"))
    held = f"{stem}.{kind}" if converted else stem
    check = {"file": os.path.relpath(f, here), "text": open(f).read(), "renderer": renderer,
             "model": os.path.join(os.path.relpath(d, here), f"{held}.json"),
             "source": os.path.join(os.path.relpath(d, here), f"{stem}.json"),
             "converted": converted, "lights": {}}
    entry = None
    if renderer != "mitsuba":
        entry = entry_of(reports[renderer], f) if renderer in reports else None
        if entry is None:
            return None
    describe(check, renderer, kind, entry)
    base = os.path.join(exr_dir, os.path.relpath(f).replace("/", "."))
    for light in lights:
        if renderer == "mitsuba":
            renders = mitsuba_renders(f, kind, light, spp)
            if renders is None:
                continue
        else:
            if light != reports[renderer]["light"]:
                continue
            renders = [read_exr(f"{base}.{light}.seed{s}.exr") for s in SEEDS]
        held_img = read_exr(os.path.join(exr_dir, "brdf-render", held, f"{light}.exr"))
        source_img = read_exr(os.path.join(exr_dir, "brdf-render", stem, f"{light}.exr"))
        check["lights"][light] = compare(held_img, source_img, renders)
        spec = f"{base}.{light}.gltf_spec.exr"
        if renderer == "materialx" and os.path.exists(spec):
            # MaterialX's GLSL with the glTF spec's formulas (materialx_gltf_spec.py).
            check["lights"][light]["flip_held_gltf_spec"] = hdr_flip(held_img, read_exr(spec))
    return check


# Significant digits of the numbers written. The renders behind them vary
# between runs (Mitsuba's and Cycles' threads sum in their own order), which
# rewrote the committed answers on every CI run: the mean colours in the
# ninth digit, the FLIPs of a re-seeded render in the sixth. Seven digits
# (four for a FLIP) stay far inside the Rust tests' tolerances (the
# recomputed brdf-render means agree to 1e-5, FLIP bounds are in the second
# digit).
DIGITS = 7
FLIP_DIGITS = 4


def rounded(x, digits=DIGITS):
    """`x` with every float rounded to `digits` significant digits (FLIP_DIGITS
    under a key naming a FLIP)."""
    if isinstance(x, float):
        return float(f"{x:.{digits}g}")
    if isinstance(x, dict):
        return {k: rounded(v, FLIP_DIGITS if "flip" in k else digits) for k, v in x.items()}
    if isinstance(x, list):
        return [rounded(v, digits) for v in x]
    return x


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
           "reference": "brdf-render (examples/judge_exr.rs), 128 px, its film (crates/brdf-render/src/film.rs)",
           "mitsuba_spp": spp, "checks": []}
    reports = renderer_reports(exr_dir)
    for renderer, report in reports.items():
        out[renderer] = settings_of(renderer, report)
    for f in files:
        check = check_file(f, exr_dir, lights, spp, reports)
        if check is not None:
            out["checks"].append(check)
    print(json.dumps(rounded(out), indent=1))


if __name__ == "__main__":
    main()
