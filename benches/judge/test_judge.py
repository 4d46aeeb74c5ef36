"""The CI judge: for every RGL file in `$BRDF_DATA/rgl`, the
default `brdf fit` (principled, fitted for appearance) exported to Mitsuba 3
and rendered in the judge scene beside Mitsuba's own `measured` plugin on
the same file, under both light sets (`docs/appearance.md`); `brdf fit
--for mitsuba` rendered the same way, `brdf fit --for blender` rendered
by Blender Cycles and (on the two films) `brdf fit --for materialx` by
MaterialX's GLSL renderer in the studio scene beside the same render; and
brdf-render's render of each measurement (what the fits for appearance are
fitted to) beside Mitsuba's, and the colour-plane bound the reports carry
beside NumPy's on that render (`colour_planes.py`).

The bounds are regression guards (the measured figures of
results/render_fidelity.md plus a stated noise margin); which goals of the
default fit are met, and by how much the others are missed, is tabulated at the
end of results/render_fidelity.md.
Run by `.ci/run` (`bash benches/judge/ci.sh`).
"""

import functools
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import colour_planes as CP  # noqa: E402
import metrics as M  # noqa: E402
import render_fidelity as RF  # noqa: E402
import scene as S  # noqa: E402

# FLIP bounds (sky, studio) and the largest mean-colour CIEDE2000: regression
# guards, not the goals. Measured (results/render_fidelity.md, 256 spp,
# brdf-render's sky = Mitsuba's sunsky tabulated) plus a noise margin of 5%
# of the value (at least 0.005) on FLIP and 0.5 on dE; the renders are
# seeded and the fits deterministic, so the margin covers platform
# differences only. All bounds lie below the Mitsuba inverse-rendering peer
# (ibiza 0.372/0.244, iris 0.443/0.266, golden yellow 0.612/0.393, colodur
# 0.111/0.096, paper 0.069/0.047), and every film's dE bound below the
# goal of 5. Measured:
# - paper_white 0.053/0.038 (the Ngan fit with sheen and clear coat, tried
#   together since ecc00fb; was cube-root + sheen, 0.057/0.041), colodur
#   0.073/0.051 (goals 0.06/0.04: paper meets both, so its bounds are
#   the goals where those are tighter; colodur misses by 0.013/0.011);
# - films fitted for Ngan's L2 (the default before fits for appearance):
#   ibiza 0.506/0.314, iris 0.638/0.450,
#   golden yellow 0.540/0.391; now 0.314/0.216 (dE 3.2), 0.330/0.230
#   (dE 1.6), 0.235/0.185 (dE 1.7): golden yellow meets every goal, ibiza
#   and iris none of the FLIP halvings (results/render_fidelity.md lists
#   each goal and its margin).
BOUNDS = {
    "paper_white_rgb": ((0.058, 0.040), 1.0),
    "colodur_napoli_4f_rgb": ((0.078, 0.056), 1.0),
    "cc_ibiza_sunset_rgb": ((0.330, 0.227), 3.8),
    "cc_iris_purple_gem_rgb": ((0.347, 0.242), 2.1),
    "vch_golden_yellow_rgb": ((0.247, 0.194), 2.2),
}


def files():
    if not os.environ.get("BRDF_DATA"):
        pytest.skip("BRDF_DATA is not set: the judge needs the RGL measurements")
    found = RF.data_dir()
    missing = set(BOUNDS) - {f.stem for f in found}
    assert not missing, f"RGL files missing from $BRDF_DATA/rgl: {sorted(missing)}"
    return found


# The same fit written on the measurement's grid (`brdf export --to mitsuba
# --tabulate-on`, how results/render_fidelity.md judges the models Mitsuba
# lacks) against its exact `principled` export, both rendered by Mitsuba:
# FLIP bounds (sky, studio) of what the tabulation alone changes, checked on
# a film and a matte material. Measured when written: cc_ibiza_sunset
# 0.077 / 0.019 (the sun's small highlight falls between the grid's nodes),
# paper_white 0.046 / 0.028 with the fit of ecc00fb (0.045 / 0.026 before;
# two renders of the measurement alone: 0.041 / 0.013 and 0.016 / 0.011);
# the bounds add 10%.
TABULATION_BOUNDS = {
    "cc_ibiza_sunset_rgb": (0.085, 0.021),
    "paper_white_rgb": (0.050, 0.031),
}


# brdf-render's own render of each measurement (the target of every fit for
# appearance) against Mitsuba's `measured` plugin's, FLIP (sky, studio).
# brdf-render evaluates the table with the camera's direction as its incident
# direction, as Mitsuba does (in the other order the films differed by up to
# 0.194 / 0.076, cc_ibiza_sunset), and lights each point by environment cells
# about its mirror direction, half-vector rings near it (brdf_render::quadrature;
# a fixed set of 512 directions showed as spots on the glossy films: iris
# 0.120 / 0.050; rings among incident directions alone: golden yellow 0.072 /
# 0.055, ibiza 0.052 / 0.019). Measured when written (Mitsuba at 256 spp
# against brdf-render's noiseless render): paper_white 0.020 / 0.010, colodur
# 0.026 / 0.017, ibiza 0.051 / 0.014, iris 0.104 / 0.031, golden yellow 0.070
# / 0.049; two Mitsuba renders of a measurement differ by 0.016-0.050 (sky)
# and 0.011-0.018 (studio). What remains on the films is at the grazing rim
# and around the sun's highlight, with equal mean colours (within 1%).
# Bounds: the measured figures plus 10% (at least 0.005).
DATA_RENDER_BOUNDS = {
    "paper_white_rgb": (0.025, 0.016),
    "colodur_napoli_4f_rgb": (0.031, 0.022),
    "cc_ibiza_sunset_rgb": (0.057, 0.019),
    "cc_iris_purple_gem_rgb": (0.115, 0.037),
    "vch_golden_yellow_rgb": (0.078, 0.054),
}


@functools.lru_cache(maxsize=None)
def measured_renders(stem):
    """Mitsuba's renders of the measurement `stem` (seed 1), once per run."""
    data = next(f for f in files() if f.stem == stem)
    S.set_variant()
    return data, RF.measured_renders(data, S.SPP)


def judge_exr():
    """brdf-render's judge renders (`examples/judge_exr.rs`), built beside `brdf`."""
    exe = os.environ.get("JUDGE_EXR") or str(Path(RF.brdf_bin()).parent / "examples" / "judge_exr")
    assert Path(exe).is_file(), f"{exe} is missing: build it with `cargo build --release --examples`"
    return exe


@pytest.mark.parametrize("stem", sorted(DATA_RENDER_BOUNDS))
def test_brdf_render_renders_the_measurement_as_mitsuba_does(stem):
    data, refs = measured_renders(stem)
    import mitsuba as mi

    with tempfile.TemporaryDirectory() as work:
        subprocess.run([judge_exr(), str(data), work], check=True)
        for light, bound in zip(S.LIGHTS, DATA_RENDER_BOUNDS[stem]):
            ours = np.array(mi.Bitmap(str(Path(work) / f"{light}.exr")), dtype=np.float32)[..., :3]
            flip = M.flip(refs[light], ours)
            print(stem, light, "brdf-render's render of the measurement against Mitsuba's: FLIP", flip)
            assert flip <= bound, (stem, light, flip)
            if light == "studio":
                studio = ours
    # The colour-plane bound every report carries (Rust, brdf_render::colour_plane)
    # against NumPy's on the same render (colour_planes.py), to the EXR's float32.
    out = subprocess.run([RF.brdf_bin(), "fit", "--data", str(data), "--model", "lambert",
                          "--json", "--quiet"], check=True, capture_output=True, text=True).stdout
    reported = json.loads(out)["image_errors"][0]["colour_plane"]["outside"]
    numpy = CP.bound(studio.astype(np.float64)[M.sphere_mask(studio.shape[0])])
    print(stem, "colour-plane bound: brdf", reported, "NumPy", numpy)
    assert abs(reported - numpy) <= 1e-4 * numpy, (stem, reported, numpy)


@pytest.mark.parametrize("stem", sorted(BOUNDS))
def test_default_fit_renders_like_the_measurement(stem):
    data, refs = measured_renders(stem)
    (flip_sky, flip_studio), max_de = BOUNDS[stem]
    with tempfile.TemporaryDirectory() as work:
        exact = {}
        row = RF.row_for(data, refs, "principled", "default", work, S.SPP, images=exact)
        if stem in TABULATION_BOUNDS:
            fit_json = Path(work) / f"{stem}.principled.default.json"
            tabulated = RF.export(fit_json, {}, "tabulated", data)
            for light, bound in zip(S.LIGHTS, TABULATION_BOUNDS[stem]):
                img = S.render(S.bsdf_of(tabulated), light, seed=2)
                flip = M.flip(exact[light], img)
                print(stem, light, "tabulated against exact: FLIP", flip)
                assert flip <= bound, (stem, light, flip)
    print(stem, row)
    assert row["sky"]["flip"] <= flip_sky, row
    assert row["studio"]["flip"] <= flip_studio, row
    assert max(row["sky"]["delta_e"], row["studio"]["delta_e"]) <= max_de, row


# `brdf fit --for mitsuba` (rendered by Mitsuba, both light sets) and `brdf
# fit --for blender` (its script rendered by Blender Cycles, studio light)
# against the measurement: regression guards on FLIP, the figures of the
# `--for` rows of results/render_fidelity.md plus 5% (at least 0.005). The
# goals (results/render_fidelity.md, "Goals of `brdf fit --for`") are not
# these bounds. Measured (sky / studio; Cycles: studio), with the model chosen:
FOR_MITSUBA_BOUNDS = {
    "cc_ibiza_sunset_rgb": (0.285, 0.152),  # 0.271 / 0.144, lobes-conductor-mitsuba, 2 lobes
    "cc_iris_purple_gem_rgb": (0.348, 0.196),  # 0.331 / 0.186, lobes-conductor-mitsuba, 2 lobes
    "colodur_napoli_4f_rgb": (0.071, 0.046),  # 0.066 / 0.040, lobes-conductor-mitsuba
    "paper_white_rgb": (0.058, 0.042),  # 0.053 / 0.036, lobes-conductor-mitsuba
    "vch_golden_yellow_rgb": (0.196, 0.133),  # 0.186 / 0.126, lobes-conductor-mitsuba, 2 lobes
}
FOR_BLENDER_BOUNDS = {
    "cc_ibiza_sunset_rgb": 0.125,  # 0.119, film-cycles
    "cc_iris_purple_gem_rgb": 0.152,  # 0.145, film-coat-cycles
    "colodur_napoli_4f_rgb": 0.046,  # 0.041, lobes-conductor-cycles
    "paper_white_rgb": 0.041,  # 0.036, film-coat-cycles
    "vch_golden_yellow_rgb": 0.131,  # 0.124, lobes-f82-coat-cycles
}


# `brdf fit --for materialx`, its document rendered by MaterialX's GLSL
# renderer (studio light), on the two films the route is for; measured
# (results/render_fidelity.md) plus 5%, with the model chosen:
FOR_MATERIALX_BOUNDS = {
    "cc_ibiza_sunset_rgb": 0.157,  # 0.149, film-materialx
    "cc_iris_purple_gem_rgb": 0.173,  # 0.164, film-materialx
}


@pytest.mark.parametrize("stem", sorted(FOR_MITSUBA_BOUNDS))
def test_for_mitsuba_renders_like_the_measurement(stem):
    data, refs = measured_renders(stem)
    with tempfile.TemporaryDirectory() as work:
        row = RF.row_for(data, refs, "for", "mitsuba", work, S.SPP)
    print(stem, row)
    for light, bound in zip(S.LIGHTS, FOR_MITSUBA_BOUNDS[stem]):
        assert row[light]["flip"] <= bound, (light, row)


@pytest.mark.skipif(not os.environ.get("BLENDER_PYTHON"),
                    reason="BLENDER_PYTHON (a python with bpy) is not set")
@pytest.mark.parametrize("stem", sorted(FOR_BLENDER_BOUNDS))
def test_for_blender_renders_in_cycles_like_the_measurement(stem):
    data, refs = measured_renders(stem)
    with tempfile.TemporaryDirectory() as work:
        row = RF.row_for(data, refs, "for", "blender", work, S.SPP)
    print(stem, row)
    assert row["studio"]["flip"] <= FOR_BLENDER_BOUNDS[stem], row


@pytest.mark.skipif(shutil.which("xvfb-run") is None,
                    reason="xvfb-run (Debian's xvfb) is not installed: MaterialX's GLSL renderer needs an X display")
@pytest.mark.parametrize("stem", sorted(FOR_MATERIALX_BOUNDS))
def test_for_materialx_renders_in_materialx_like_the_measurement(stem):
    data, refs = measured_renders(stem)
    with tempfile.TemporaryDirectory() as work:
        row = RF.row_for(data, refs, "for", "materialx", work, S.SPP)
    print(stem, row)
    assert row["studio"]["flip"] <= FOR_MATERIALX_BOUNDS[stem], row
