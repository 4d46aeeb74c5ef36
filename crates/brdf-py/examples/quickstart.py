"""The README's Python example: fit a CUReT material, evaluate the fitted
model on NumPy arrays, save and reload it, export it. Run with BRDF_DATA
set to the measured data folder."""

import os
import sys
import tempfile
from pathlib import Path

import numpy as np

import brdf


def main() -> None:
    if not os.environ.get("BRDF_DATA"):
        sys.exit("set BRDF_DATA to the folder with the measured data")
    fit = brdf.fit("curet/abrdf.dat#25", "blinn-phong")  # looked up under BRDF_DATA
    print(fit)  # Fit(model="blinn-phong", data="curet/abrdf.dat#25", ngan_l2=[...])
    print(fit.model.params)  # {'kd': ..., 'ks': ..., 'n': ...}
    print(fit.report["fits"][0]["ngan_l2"])

    theta = np.linspace(0.0, 1.2, 5)
    wi = np.stack([np.sin(theta), np.zeros_like(theta), np.cos(theta)], axis=1)
    wo = np.array([0.0, 0.0, 1.0])
    values = fit.model.eval(wi, wo)  # (5, channels), 1/sr
    print(values.shape)
    image = fit.model.render(light="studio")  # the judge's sphere, linear radiance
    print(image.shape, float(image.max()))

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "fit.json"
        fit.model.save(path)
        again = brdf.Model.load(path)
        assert np.array_equal(again.eval(wi, wo), values)
    print(brdf.Fit.__doc__ is not None, fit.image_error)
    try:
        print(fit.model.export(to="mitsuba")[:60])
    except brdf.BrdfError as e:  # no exact equivalent in that renderer
        print(f"not exported: {e}")


if __name__ == "__main__":
    main()
