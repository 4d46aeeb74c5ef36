"""What colour alone costs a model with one base colour: every
principled and glTF lobe is white or the base colour, so under the judge's
white `studio` light every render of such a model has all its colours in
one plane of white and one colour (brdf_render::colour_plane). For each RGL
measurement in `$BRDF_DATA/rgl`, under `studio`:

- `bound`: the relative RMS (linear RGB) of the measurement's colours off the
  closest such plane (its chroma's principal axis), computed here with
  NumPy on brdf-render's render of the measurement (`examples/judge_exr`),
  beside the figure `brdf fit --json` reports (`image_errors[0].colour_plane`,
  Rust): no principled or glTF render comes closer to that render;
- `FLIP, colour moved`: Mitsuba's `measured` render of the measurement (the
  judge's reference: seed 1, 256 samples per pixel) with every pixel moved to
  the nearest colour of a plane of white and one colour (least squares in
  FLIP's linear opponent space YCxCz, the plane's hue scanned), HDR-FLIP
  against the unmoved render, least over the planes. The moved render keeps
  everything else of the measurement, so this estimates what the colour
  restriction alone costs before any error of shape or noise; it is not a
  bound (HDR-FLIP is no distance a projection minimises).

Writes `results/colour_planes.md`. Run from the repository root, in the
judge's venv, after `cargo build --release -p brdf-cli --examples`:

    python benches/judge/colour_planes.py
"""

import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import metrics as M  # noqa: E402
import render_fidelity as RF  # noqa: E402
import scene as S  # noqa: E402

WHITE = np.ones(3) / np.sqrt(3.0)
E1 = np.array([1.0, -1.0, 0.0]) / np.sqrt(2.0)
E2 = np.cross(WHITE, E1)
# Linear sRGB (D65) to XYZ, then XYZ to FLIP's YCxCz (Y' = 116 Y/Yn, Cx =
# 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn)): linear in RGB.
RGB_TO_XYZ = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])
_WP = RGB_TO_XYZ @ np.ones(3)
XYZ_TO_YCXCZ = np.array([[0.0, 116.0 / _WP[1], 0.0],
                         [500.0 / _WP[0], -500.0 / _WP[1], 0.0],
                         [0.0, 200.0 / _WP[1], -200.0 / _WP[2]]])
OPPONENT = XYZ_TO_YCXCZ @ RGB_TO_XYZ


def bound(colours):
    """Relative RMS of `colours` (n x 3, linear RGB) off the closest plane
    through white: the chroma's smallest principal spread over the energy."""
    chroma = np.stack([colours @ E1, colours @ E2], axis=-1)
    _, vecs = np.linalg.eigh(chroma.T @ chroma)
    axis = vecs[:, -1]
    across = chroma @ np.array([-axis[1], axis[0]])
    return float(np.sqrt((across ** 2).sum() / (colours ** 2).sum()))


def moved(img, mask, hue):
    """`img` with every sphere pixel at the nearest colour `a (1,1,1) + b C`
    (b >= 0, C of chroma angle `hue`) in the opponent metric."""
    c = 0.5 * WHITE + 0.5 * (np.cos(hue) * E1 + np.sin(hue) * E2)
    a, b = OPPONENT @ np.ones(3), OPPONENT @ c
    px = img[mask].astype(np.float64) @ OPPONENT.T
    gram = np.array([[a @ a, a @ b], [a @ b, b @ b]])
    sol = np.stack([px @ a, px @ b], axis=-1) @ np.linalg.inv(gram).T
    neg = sol[:, 1] < 0.0
    sol[neg, 1] = 0.0
    sol[neg, 0] = (px[neg] @ a) / (a @ a)
    out = img.copy()
    out[mask] = sol[:, :1] * np.ones(3) + sol[:, 1:] * c
    return out.astype(np.float32)


def least_flip(img):
    """Least HDR-FLIP of `moved(img)` against `img` over the planes' hues:
    2-degree steps, then 0.1-degree steps about the best."""
    mask = M.sphere_mask(img.shape[0])
    flip_at = lambda h: M.flip(img, moved(img, mask, h))  # noqa: E731
    coarse = np.radians(np.arange(0.0, 360.0, 2.0))
    best = coarse[int(np.argmin([flip_at(h) for h in coarse]))]
    fine = best + np.radians(np.arange(-2.0, 2.05, 0.1))
    return min(flip_at(h) for h in fine)


def reported_bound(data):
    """`image_errors[0].colour_plane.outside` of `brdf fit --json` (the
    default principled fit) on `data`."""
    out = subprocess.run([RF.brdf_bin(), "fit", "--data", str(data), "--model", "principled",
                          "--channels", "rgb", "--json", "--quiet"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["image_errors"][0]["colour_plane"]["outside"]


def brdf_render_studio(data, judge_exr):
    """brdf-render's studio render of `data` (`examples/judge_exr`)."""
    import mitsuba as mi

    with tempfile.TemporaryDirectory() as work:
        subprocess.run([judge_exr, str(data), work], check=True, capture_output=True)
        return np.array(mi.Bitmap(str(Path(work) / "studio.exr")), dtype=np.float64)[..., :3]


def main():
    S.set_variant()
    judge_exr = str(Path(RF.brdf_bin()).parent / "examples" / "judge_exr")
    lines = [
        "# What colour alone costs a renderer model with one base colour",
        "",
        "Written by `python benches/judge/colour_planes.py` (its docstring says how).",
        "Every principled and glTF lobe is white or the base colour, so under the white",
        "`studio` light every render of those models lies in one plane of white and one",
        "colour. `bound`: the relative RMS (linear RGB) of brdf-render's 128-px render of",
        "the measurement off the closest such plane, by NumPy here and as `brdf fit` reports",
        "it: no principled or glTF render comes closer. `FLIP, colour moved`: Mitsuba's",
        "`measured` render (the judge's reference, seed 1, 256 spp) with every pixel moved",
        "to the nearest colour of the best such plane (in FLIP's linear opponent space),",
        "against the unmoved render: an estimate of what the colour restriction alone",
        "costs before any error of shape or noise (not a bound). `goal` and `default fit`:",
        "the studio FLIP goal of the default fit and the default principled fit's studio FLIP",
        "(results/render_fidelity.md).",
        "",
        "| material | bound (NumPy) | bound (`brdf fit`) | FLIP, colour moved | goal | default fit |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    table = json.loads((RF.ROOT / "results" / "render_fidelity" / "table.json").read_text())
    for data in RF.data_dir():
        img = brdf_render_studio(data, judge_exr)
        ours = bound(img[M.sphere_mask(img.shape[0])])
        reference = S.render(S.bsdf_of(data), "studio", seed=1)
        fit = next((r["studio"]["flip"] for r in table if r["material"] == data.stem
                    and r["model"] == "principled" and r["objective"] == "default"), None)
        goal = RF.GOALS.get(data.stem, ((None, None),))[0][1]
        fmt = lambda x: "-" if x is None else f"{x:.3f}"  # noqa: E731
        lines.append(f"| {data.stem} | {ours:.4f} | {reported_bound(data):.4f} | "
                     f"{least_flip(reference):.3f} | {fmt(goal)} | {fmt(fit)} |")
        print(lines[-1], flush=True)
    (RF.ROOT / "results" / "colour_planes.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
