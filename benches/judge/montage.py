"""README picture: for one material, the measurement (Mitsuba's `measured`
plugin), the default fit and the Ngan-L2 fit of before issue 23, rendered by
Mitsuba 3 under both light sets (tiles written by render_fidelity.py).

    python benches/judge/montage.py cc_iris_purple_gem_rgb principled OUT.png
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
    material, model, out = sys.argv[1:4]
    rows = []
    for light in ("sky", "studio"):
        names = [f"{material}.measured.{light}.png", f"{material}.{model}.default.{light}.png",
                 f"{material}.{model}.ngan.{light}.png"]
        rows.append(np.concatenate([tile(n) for n in names], axis=1))
    img = np.ascontiguousarray(np.concatenate(rows, axis=0))
    mi.Bitmap(img, pixel_format=mi.Bitmap.PixelFormat.RGB).write(out)


if __name__ == "__main__":
    main()
