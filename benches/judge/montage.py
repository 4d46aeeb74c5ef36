"""The pictures of docs/ (docs/render_fidelity_iris.png,
docs/new_models_ibiza.png): for one material, the measurement (Mitsuba's `measured`
plugin) and some fits, rendered by Mitsuba 3 under both light sets (the
tiles render_fidelity.py writes into results/render_fidelity/; a fit's tile
is named `MODEL.OBJECTIVE[.tabulated]`), one row per light set.

    python benches/judge/montage.py cc_iris_purple_gem_rgb OUT.png principled.default principled.ngan
    python benches/judge/montage.py cc_ibiza_sunset_rgb OUT.png principled.default sgd.appearance.tabulated
"""

import sys
from pathlib import Path

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
ROOT = Path(__file__).resolve().parents[2] / "results" / "render_fidelity"


def tile(name):
    return np.array(mi.Bitmap(str(ROOT / name)))


def main():
    material, out, *fits = sys.argv[1:]
    if not fits:
        sys.exit(__doc__)
    rows = []
    for light in ("sky", "studio"):
        names = [f"{material}.measured.{light}.png"] + [f"{material}.{f}.{light}.png" for f in fits]
        rows.append(np.concatenate([tile(n) for n in names], axis=1))
    img = np.ascontiguousarray(np.concatenate(rows, axis=0))
    mi.Bitmap(img, pixel_format=mi.Bitmap.PixelFormat.RGB).write(out)


if __name__ == "__main__":
    main()
