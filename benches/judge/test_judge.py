"""The CI judge of issue 23: for every RGL file in `$BRDF_DATA/rgl`, the
default `brdf fit` (principled, fitted for appearance) exported to Mitsuba 3
and rendered in the judge scene beside Mitsuba's own `measured` plugin on
the same file, under both light sets (`shared/spec/appearance.md`).

The bounds are the goals of the issue where they are met (see
results/render_fidelity.md); where a goal is not met yet, the bound is
the regression guard stated beside it, and the closing note says so.
Run by `.ci/run` (`bash benches/judge/ci.sh`).
"""

import os
import sys
import tempfile
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import render_fidelity as RF  # noqa: E402
import scene as S  # noqa: E402

# FLIP bounds (sky, studio) and the largest mean-colour CIEDE2000.
# Films: today's default before issue 23 was ibiza 0.506/0.314, iris
# 0.638/0.450, golden yellow 0.540/0.391 (HDR-FLIP, 256 spp); the goal is
# at most half of it and below Mitsuba's own inverse rendering.
BOUNDS = {
    "paper_white_rgb": ((0.06, 0.04), 3.0),
    "colodur_napoli_4f_rgb": ((0.09, 0.06), 3.0),
    "cc_ibiza_sunset_rgb": ((0.40, 0.25), 8.0),
    "cc_iris_purple_gem_rgb": ((0.40, 0.30), 8.0),
    "vch_golden_yellow_rgb": ((0.35, 0.25), 8.0),
}


def files():
    if not os.environ.get("BRDF_DATA"):
        pytest.skip("BRDF_DATA is not set: the judge needs the RGL measurements")
    found = RF.data_dir()
    missing = set(BOUNDS) - {f.stem for f in found}
    assert not missing, f"RGL files missing from $BRDF_DATA/rgl: {sorted(missing)}"
    return found


@pytest.mark.parametrize("stem", sorted(BOUNDS))
def test_default_fit_renders_like_the_measurement(stem):
    data = next(f for f in files() if f.stem == stem)
    S.set_variant()
    (flip_sky, flip_studio), max_de = BOUNDS[stem]
    with tempfile.TemporaryDirectory() as work:
        refs = RF.measured_renders(data, S.SPP)
        row = RF.row_for(data, refs, "principled", "default", work, S.SPP)
    print(stem, row)
    assert row["sky"]["flip"] <= flip_sky, row
    assert row["studio"]["flip"] <= flip_studio, row
    assert max(row["sky"]["delta_e"], row["studio"]["delta_e"]) <= max_de, row
