"""The judge's image metrics (`docs/appearance.md`), all from
maintained implementations: HDR-FLIP from NVIDIA's `flip_evaluator`,
CIEDE2000 from `colour-science`; PSNR is the textbook formula on images
exposed by `1 / p99(reference)`, clipped to [0, 1] and gamma 2.2 encoded.

Every metric reads both renders as a display shows them, negative channels
clipped at 0: Mitsuba's `measured` plugin renders out-of-gamut colours with
negative channels, and an error against a negative reference counts what
no display can show.
"""

import numpy as np
import colour
import flip_evaluator


def sphere_mask(size):
    """Pixels whose centre ray hits the unit sphere of the judge scene."""
    # Camera at z = 6, fov 22 deg (horizontal = vertical for a square film).
    t = np.tan(np.radians(22.0) / 2.0)
    c = (np.arange(size) + 0.5) / size * 2.0 - 1.0
    x, y = np.meshgrid(c * t, -c * t)
    d = np.stack([x, y, -np.ones_like(x)], axis=-1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    o = np.array([0.0, 0.0, 6.0])
    b = d @ o
    disc = b * b - (o @ o - 1.0)
    return disc > 0.0


def shown(img):
    """The render as a display shows it: negative channels clipped at 0."""
    return np.ascontiguousarray(np.maximum(img, 0.0), dtype=np.float32)


def flip(reference, test):
    """Mean HDR-FLIP over the whole image (background included)."""
    _, mean, _ = flip_evaluator.evaluate(shown(reference), shown(test), "HDR")
    return float(mean)


def exposure(reference):
    return 1.0 / max(float(np.percentile(shown(reference), 99)), 1e-12)


def ldr(img, exp):
    return np.clip(np.maximum(img, 0.0) * exp, 0.0, 1.0) ** (1.0 / 2.2)


def psnr(reference, test):
    e = exposure(reference)
    mse = float(np.mean((ldr(reference, e) - ldr(test, e)) ** 2))
    return float("inf") if mse == 0.0 else 10.0 * np.log10(1.0 / mse)


def mean_colour(img):
    m = sphere_mask(img.shape[0])
    return shown(img)[m].mean(axis=0)


def delta_e(reference, test):
    """CIEDE2000 between the mean linear-sRGB colours of the sphere pixels,
    both scaled by the reference's exposure so the reference's mean has
    a luminance a display shows."""
    a, b = mean_colour(reference), mean_colour(test)
    s = 0.5 / max(float(colour.sRGB_to_XYZ(a, apply_cctf_decoding=False)[1]), 1e-12)
    lab = [
        colour.XYZ_to_Lab(colour.sRGB_to_XYZ(c * s, apply_cctf_decoding=False))
        for c in (a, b)
    ]
    return float(colour.delta_E(lab[0], lab[1], method="CIE 2000"))


def tonemapped_png(img, path, exp):
    """8-bit sRGB PNG of a render at the given exposure (for pictures),
    written by Mitsuba's own bitmap writer."""
    import mitsuba as mi

    lin = np.ascontiguousarray(np.clip(np.maximum(img, 0.0) * exp, 0.0, 1.0), dtype=np.float32)
    bmp = mi.Bitmap(lin, pixel_format=mi.Bitmap.PixelFormat.RGB)
    bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=True).write(str(path))
