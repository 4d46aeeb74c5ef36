"""The judge scene of `docs/appearance.md`, in Mitsuba 3 (variant
`scalar_rgb` by default): a unit sphere carrying a BSDF, the perspective
camera at (0, 0, 6) with a 22 deg field of view, `path` with max_depth 2,
and the two light sets "sky" (`sunsky`, sun at (0.5, 0.64, 0.58)) and
"studio" (a 0.05 constant fill and a 1.2 x 1.2 area light of radiance 12 at
(3, 3, 4) aimed at the sphere).

A BSDF is given either as a Mitsuba XML file written by `brdf export --to
mitsuba` (loaded with `mi.load_file`, which accepts a file whose root is a
`<bsdf>`), or as an RGL `.bsdf` measurement (rendered by Mitsuba's own
`measured` plugin, the reference).

Used by `render_fidelity.py` (the table of results/render_fidelity.md) and
by the CI judge test.
"""

import mitsuba as mi

LIGHTS = ("sky", "studio")
SIZE = 128
SPP = 256


def set_variant(name="scalar_rgb"):
    if mi.variant() != name:
        mi.set_variant(name)
    # The `measured` plugin's spectral-to-RGB step gives slightly negative
    # red on saturated blue films; Mitsuba warns once per sample.
    mi.set_log_level(mi.LogLevel.Error)


def bsdf_of(path):
    """The BSDF dict/object of a measurement (`.bsdf`) or an exported fit (`.xml`)."""
    path = str(path)
    if path.endswith(".bsdf"):
        return {"type": "measured", "filename": path}
    # `brdf export --to mitsuba` writes a paste-in `<bsdf ...>` snippet
    # without the `version` attribute a file of its own needs.
    with open(path, encoding="utf-8") as f:
        xml = f.read()
    if 'version="' not in xml.split("<bsdf", 1)[1].split(">", 1)[0]:
        xml = xml.replace("<bsdf", '<bsdf version="3.0.0"', 1)
    return mi.load_string(xml)


def emitters(light):
    if light == "sky":
        return {
            "sky": {"type": "sunsky", "sun_direction": [0.5, 0.64, 0.58]},
        }
    if light == "studio":
        T = mi.ScalarTransform4f
        return {
            "fill": {"type": "constant", "radiance": {"type": "rgb", "value": 0.05}},
            "key": {
                "type": "rectangle",
                "to_world": T().look_at(origin=[3, 3, 4], target=[0, 0, 0], up=[0, 1, 0])
                @ T().scale(0.6),
                "emitter": {"type": "area", "radiance": {"type": "rgb", "value": 12.0}},
            },
        }
    raise ValueError(f"unknown light set {light!r}: sky or studio")


def scene(bsdf, light, size=SIZE, spp=SPP, integrator="path"):
    T = mi.ScalarTransform4f
    d = {
        "type": "scene",
        "integrator": {"type": integrator, "max_depth": 2},
        "sensor": {
            "type": "perspective",
            "fov": 22,
            "to_world": T().look_at(origin=[0, 0, 6], target=[0, 0, 0], up=[0, 1, 0]),
            "film": {"type": "hdrfilm", "width": size, "height": size, "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": spp},
        },
        "sphere": {"type": "sphere", "bsdf": bsdf},
    }
    d.update(emitters(light))
    return mi.load_dict(d)


def render(bsdf, light, seed, size=SIZE, spp=SPP):
    """Linear RGB radiance, float32 numpy array (size, size, 3)."""
    import numpy as np

    img = mi.render(scene(bsdf, light, size, spp), seed=seed)
    return np.array(img, dtype=np.float32)[:, :, :3]
