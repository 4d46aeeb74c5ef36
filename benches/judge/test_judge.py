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
# Measured (results/render_fidelity.md, 256 spp) and the goals:
# - paper_white 0.057/0.041 and colodur 0.087/0.059: the goals (0.06/0.04)
#   hold for paper_white's sky only; colodur is at Ngan's fit (0.081/0.058)
#   and both lie within 0.02-0.04 of the two-seed noise floor;
# - films, before issue 23 (Ngan's L2): ibiza 0.506/0.314, iris 0.638/0.450,
#   golden yellow 0.540/0.391; now 0.322/0.213, 0.335/0.254, 0.297/0.197:
#   below Mitsuba's own inverse rendering (0.372/0.244, 0.443/0.266,
#   0.612/0.393) everywhere, at half of before only for golden yellow's
#   studio light. The bounds: below the inverse-rendering peer, and a
#   margin of about 10% over what was measured.
BOUNDS = {
    "paper_white_rgb": ((0.065, 0.046), 1.0),
    "colodur_napoli_4f_rgb": ((0.097, 0.066), 1.0),
    "cc_ibiza_sunset_rgb": ((0.36, 0.24), 5.5),
    "cc_iris_purple_gem_rgb": ((0.37, 0.265), 6.5),
    "vch_golden_yellow_rgb": ((0.33, 0.22), 7.6),
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
