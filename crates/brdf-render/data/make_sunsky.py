"""Tabulate Mitsuba 3's `sunsky` emitter for brdf-render's "sky" light set.

The judge scene (`docs/appearance.md`) lights the sphere with
Mitsuba 3.9.1's `sunsky` emitter, `sun_direction = [0.5, 0.64, 0.58]`, every
other parameter at its default (turbidity 3, ground albedo 0.3, sun aperture
0.5358 deg, the simple uniform sun disc). Instead of reimplementing the
Hosek-Wilkie sky and its datasets, this script asks Mitsuba itself
(`Emitter.eval` with `si.wi` = minus the world direction towards the sky) and
writes `sunsky_table.rs`, a Rust fragment that `brdf-render/src/sky.rs`
includes:

- the sky alone (the emitter with `sun_scale = 0`), RGB radiance on a grid
  over the upper hemisphere in (zenith angle `theta`, azimuth from the sun's
  `dphi` in [0, pi]); the sky is symmetric about the sun's vertical plane
  (checked below). Rows are uniform in `x = 1 - sqrt(1 - theta / (pi / 2))`
  (finer towards the bright horizon), columns uniform in `dphi`; bilinear
  interpolation in `(x, dphi)` reproduces Mitsuba to the error printed below;
- the sun alone (`sky_scale = 0`): its direction and its RGB irradiance at
  normal incidence, the radiance of its uniform disc integrated over the
  disc (numerically, checked against `L * 2 pi (1 - cos(aperture / 2))`);
- check values: Mitsuba's sky radiance at random directions, which the Rust
  tests compare with the interpolated table.

Mitsuba's world zenith is `+z` (found by evaluating: the emitter is black for
every direction with `z < 0` and darkest blue at `+z`): the judge camera at
`(0, 0, 6)` looks straight down at the sphere, so its background is the
black ground and the sun stands 35.5 deg above the horizon.

Run from anywhere (it writes beside itself), in the judge's venv
(`benches/judge/requirements.txt`):

    python crates/brdf-render/data/make_sunsky.py
"""

import math
from pathlib import Path

import mitsuba as mi
import numpy as np

SUN = [0.5, 0.64, 0.58]
ROWS = 46  # x = 1 - sqrt(1 - theta / (pi / 2)) in [0, 1]
COLS = 61  # dphi in [0, pi], 3 deg steps
CHECKS = 64
OUT = Path(__file__).resolve().parent / "sunsky_table.rs"


def emitter(**kw):
    return mi.load_dict({"type": "sunsky", "sun_direction": SUN, **kw})


def evaluator(em):
    si = mi.SurfaceInteraction3f()

    def radiance(d):
        si.wi = mi.Vector3f(*(-np.asarray(d, dtype=float)))
        return np.array(em.eval(si), dtype=float)

    return radiance


def direction(theta, dphi, phi_sun):
    ph = phi_sun + dphi
    return np.array(
        [math.sin(theta) * math.cos(ph), math.sin(theta) * math.sin(ph), math.cos(theta)]
    )


def theta_of_row(i):
    x = i / (ROWS - 1)
    return (1.0 - (1.0 - x) ** 2) * math.pi / 2.0


def interpolate(table, theta, dphi):
    x = (1.0 - math.sqrt(max(0.0, 1.0 - theta / (math.pi / 2.0)))) * (ROWS - 1)
    y = dphi / math.pi * (COLS - 1)
    i, j = min(int(x), ROWS - 2), min(int(y), COLS - 2)
    fx, fy = x - i, y - j
    return (
        table[i, j] * (1 - fx) * (1 - fy)
        + table[i + 1, j] * fx * (1 - fy)
        + table[i, j + 1] * (1 - fx) * fy
        + table[i + 1, j + 1] * fx * fy
    )


def fmt(v):
    return "[" + ", ".join(f"{x:.6e}" for x in v) + "]"


def main():
    mi.set_variant("scalar_rgb")
    full, sky, sun = emitter(), evaluator(emitter(sun_scale=0.0)), evaluator(emitter(sky_scale=0.0))
    props = str(full)
    s = np.array(SUN, dtype=float)
    s /= np.linalg.norm(s)
    phi_sun = math.atan2(s[1], s[0])
    # The zenith: nothing below the z = 0 plane, bluish and dim at +z.
    assert np.all(sky([0.3, 0.2, -0.5]) == 0.0) and np.all(sky([0, 0, -1]) == 0.0)
    zen = sky([0, 0, 1])
    assert zen[2] > zen[0] > 0.0, zen

    table = np.array(
        [[sky(direction(theta_of_row(i), math.pi * j / (COLS - 1), phi_sun)) for j in range(COLS)]
         for i in range(ROWS)]
    )
    # Symmetry about the sun's vertical plane, which the table assumes.
    rng = np.random.default_rng(23)
    for _ in range(200):
        th, dp = rng.random() * math.pi / 2, rng.random() * math.pi
        a, b = sky(direction(th, dp, phi_sun)), sky(direction(th, -dp, phi_sun))
        assert np.allclose(a, b, rtol=1e-5, atol=1e-9), (th, dp, a, b)
    # Interpolation error against Mitsuba at random directions of the upper
    # hemisphere (uniform in solid angle).
    errs = []
    for _ in range(4000):
        th, dp = math.acos(rng.random()), rng.random() * math.pi
        ref = sky(direction(th, dp, phi_sun))
        errs.append(np.max(np.abs(interpolate(table, th, dp) - ref) / ref))
    errs = np.array(errs)
    checks = []
    for _ in range(CHECKS):
        th, dp = math.acos(rng.random()), (rng.random() * 2 - 1) * math.pi
        d = direction(th, dp, phi_sun)
        checks.append((d, sky(d)))

    # The sun: uniform radiance over a cone of half-angle aperture / 2.
    l_sun = sun(s)
    aperture = float(props.split("Sun aperture =")[1].split()[0])
    half = math.radians(aperture) / 2.0
    t1 = np.cross(s, [0.0, 0.0, 1.0])
    t1 /= np.linalg.norm(t1)
    t2 = np.cross(s, t1)
    n = 400
    e_num = np.zeros(3)
    for a in (np.arange(n) + 0.5) / n * 1.2 * half:  # rings beyond the edge too
        for b in (np.arange(64) + 0.5) / 64 * 2 * math.pi:
            d = math.cos(a) * s + math.sin(a) * (math.cos(b) * t1 + math.sin(b) * t2)
            e_num += sun(d) * math.cos(a) * math.sin(a) * (1.2 * half / n) * (2 * math.pi / 64)
    e_cone = l_sun * 2 * math.pi * (1 - math.cos(half))
    assert np.allclose(e_num, e_cone, rtol=1e-2), (e_num, e_cone)

    lines = [
        "// Generated by make_sunsky.py from Mitsuba's `sunsky` emitter; do not edit.",
        "// See sky.rs and make_sunsky.py for what the values are.",
        "//",
        f"// Mitsuba {mi.__version__}, variant scalar_rgb; the emitter as Mitsuba prints it:",
        *[f"// {line.strip()}" for line in props.splitlines()],
        "//",
        "// Bilinear interpolation of the table against Mitsuba at 4000 random upper-hemisphere",
        f"// directions: relative error mean {errs.mean():.2e}, 99th percentile"
        f" {np.percentile(errs, 99):.2e}, max {errs.max():.2e}.",
        "",
        "/// Mitsuba version the table was made with.",
        f'pub const MITSUBA_VERSION: &str = "{mi.__version__}";',
        "/// Unit sun direction (world, zenith `+z`).",
        f"pub const SUN_DIRECTION: [f64; 3] = {fmt(s)};",
        "/// RGB radiance of the sun's disc.",
        f"pub const SUN_RADIANCE: [f64; 3] = {fmt(l_sun)};",
        "/// Angular diameter of the sun's disc (degrees).",
        f"pub const SUN_APERTURE_DEG: f64 = {aperture};",
        "/// RGB irradiance of the sun at normal incidence (radiance times the disc's solid angle).",
        f"pub const SUN_IRRADIANCE: [f64; 3] = {fmt(e_cone)};",
        "/// Table rows: `x = 1 - sqrt(1 - theta / (pi / 2))` uniform in [0, 1].",
        f"pub const ROWS: usize = {ROWS};",
        "/// Table columns: azimuth from the sun `dphi` uniform in [0, pi].",
        f"pub const COLS: usize = {COLS};",
        "/// Sky RGB radiance (sun excluded), row-major (`row * COLS + col`).",
        f"pub static SKY: [[f64; 3]; {ROWS * COLS}] = [",
        *[f"    {fmt(table[i, j])}," for i in range(ROWS) for j in range(COLS)],
        "];",
        "/// Mitsuba's sky radiance at random world directions: (direction, RGB).",
        f"pub static CHECKS: [([f64; 3], [f64; 3]); {CHECKS}] = [",
        *[f"    ({fmt(d)}, {fmt(v)})," for d, v in checks],
        "];",
    ]
    OUT.write_text("\n".join(lines) + "\n")
    print(f"wrote {OUT.name}: sun irradiance {e_cone} (numerical {e_num}); "
          f"interpolation error mean {errs.mean():.2e} max {errs.max():.2e}")


if __name__ == "__main__":
    main()
