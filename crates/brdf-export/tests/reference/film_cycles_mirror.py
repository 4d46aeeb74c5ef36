"""Is Cycles' thin film the thin-film models' formula? Render a mirror sphere
(roughness 0) under a uniform white world (strength 1) with an orthographic
camera: each pixel then shows the film's reflectance A(mu) at the incidence
cosine mu = sqrt(1 - r^2) of its position r (sphere radii from the centre),
almost without noise (a delta BSDF seeing a constant world; what is left
comes from where in its pixel each sample falls). Compare it with the NumPy
A_c(mu) of crates/brdf-models/tests/reference/thin_film.py (the formula:
exact spectral Airy, CIE 1931 CMFs alone, i.e. under the equal-energy
illuminant E, linear sRGB) for several films (thickness d, film index n2,
base index n3), d = 0 (plain Fresnel) among them.

Two nodes carry the film: the Metallic BSDF (physical conductor, IOR
(n3, n3, n3), Extinction 0, GGX, Roughness 0) and the Principled BSDF
(Metallic 0, Specular IOR Level 0.5, IOR n3, Base Color black). Each film is
rendered with each, and once more without the film (thickness 0) to see
whether the node applies it at all; one film once more with another seed
(the render noise).

Pixels are taken within one pixel of the radius of each incidence angle
0, 10, ..., 70 degrees; per pixel the deviation is Cycles' value minus
A_c(mu) at that pixel's own mu. Per angle the file holds the means of ours,
of Cycles' and of the deviation, the largest deviation and its spread over
those pixels; `summary` holds the worst of these up to 60 and 70 degrees
(films, and without a film), the two seeds' largest difference and the two
nodes' largest difference.

Run with a Python that has bpy (5.0.1) and numpy (lobes_check.sh runs it
when BLENDER_PYTHON is set):
    python film_cycles_mirror.py
writes film/cycles_mirror.json beside this script (tests/export/film_cycles.rs
reads it). About a minute on two cores.
"""

import json
import pathlib
import sys
import tempfile

import bpy
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[2] / "brdf-models" / "tests" / "reference"))
import thin_film  # noqa: E402

OUT = HERE / "film" / "cycles_mirror.json"
RES = 128
SAMPLES = 128
ORTHO_SCALE = 2.2  # sphere of radius 1 with a margin
ANGLES_DEG = [0, 10, 20, 30, 40, 50, 60, 70]
FILMS = [(d, n2, n3) for d, n2, n3 in thin_film.REFLECTANCE_SETS]
NOISE_FILM = (400.0, 1.8, 2.5)


def scene_setup():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = "CYCLES"
    sc.cycles.device = "CPU"
    sc.cycles.samples = SAMPLES
    sc.cycles.use_adaptive_sampling = False
    sc.cycles.use_denoising = False
    sc.cycles.max_bounces = 4
    sc.cycles.filter_width = 0.01  # sample at pixel centres
    sc.cycles.seed = 1
    sc.render.threads_mode = "FIXED"
    sc.render.threads = 2
    sc.render.resolution_x = RES
    sc.render.resolution_y = RES
    sc.render.resolution_percentage = 100
    sc.render.film_transparent = False
    sc.view_settings.view_transform = "Standard"
    sc.view_settings.look = "None"
    sc.view_settings.exposure = 0.0
    sc.view_settings.gamma = 1.0
    sc.render.image_settings.file_format = "OPEN_EXR"
    sc.render.image_settings.color_depth = "32"
    sc.render.image_settings.exr_codec = "ZIP"

    world = bpy.data.worlds.new("white")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bg.inputs["Strength"].default_value = 1.0
    sc.world = world

    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=7, radius=1.0, location=(0, 0, 0))
    sphere = bpy.context.active_object
    bpy.ops.object.shade_smooth()

    cam_data = bpy.data.cameras.new("cam")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = ORTHO_SCALE
    cam = bpy.data.objects.new("cam", cam_data)
    cam.location = (0.0, 0.0, 10.0)  # looking down -z, up +y
    sc.collection.objects.link(cam)
    sc.camera = cam
    return sc, sphere


def material(node, d, n2, n3):
    m = bpy.data.materials.new(f"{node}_{d}_{n2}_{n3}")
    m.use_nodes = True
    nt = m.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    if node == "metallic":
        b = nt.nodes.new("ShaderNodeBsdfMetallic")
        b.fresnel_type = "PHYSICAL_CONDUCTOR"
        b.distribution = "GGX"
        b.inputs["IOR"].default_value = (n3, n3, n3)
        b.inputs["Extinction"].default_value = (0.0, 0.0, 0.0)
        b.inputs["Roughness"].default_value = 0.0
    else:
        b = nt.nodes.new("ShaderNodeBsdfPrincipled")
        b.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        b.inputs["Metallic"].default_value = 0.0
        b.inputs["Roughness"].default_value = 0.0
        b.inputs["IOR"].default_value = n3
        b.inputs["Specular IOR Level"].default_value = 0.5
    b.inputs["Thin Film Thickness"].default_value = d
    b.inputs["Thin Film IOR"].default_value = n2
    nt.links.new(b.outputs[0], out.inputs["Surface"])
    return m


def render(sc, sphere, mat, tmp):
    sphere.data.materials.clear()
    sphere.data.materials.append(mat)
    path = str(pathlib.Path(tmp) / f"{mat.name}.exr")
    sc.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    px = np.array(img.pixels[:], dtype=float).reshape(RES, RES, 4)[:, :, :3]
    bpy.data.images.remove(img)
    return px


def pixel_radius():
    """Radius (sphere radii) of each pixel centre; rows bottom to top."""
    c = (np.arange(RES) + 0.5) / RES * ORTHO_SCALE - ORTHO_SCALE / 2.0
    x, y = np.meshgrid(c, c)
    return np.hypot(x, y)


def compare(px, d, n2, n3, r):
    step = ORTHO_SCALE / RES
    rows = []
    for deg in ANGLES_DEG:
        mu = float(np.cos(np.radians(deg)))
        sel = np.abs(r - np.sin(np.radians(deg))) <= step
        mus = np.sqrt(1.0 - r[sel] ** 2)
        ours = np.array(thin_film.A(mus, d, n2, n3, 3))
        cyc = px[sel]
        dev = cyc - ours
        rows.append(
            {
                "theta_deg": deg,
                "mu": mu,
                "pixels": int(sel.sum()),
                "ours_at_mu": thin_film.A(mu, d, n2, n3, 3),
                "ours": ours.mean(axis=0).tolist(),
                "cycles": cyc.mean(axis=0).tolist(),
                "deviation": dev.mean(axis=0).tolist(),
                "max_deviation": np.abs(dev).max(axis=0).tolist(),
                "spread": dev.std(axis=0).tolist(),
            }
        )
    return rows


def worst(entry, key, up_to_deg):
    return max(max(a[key]) for a in entry["angles"] if a["theta_deg"] <= up_to_deg)


def main():
    sc, sphere = scene_setup()
    r = pixel_radius()
    inside = r < 0.94  # up to 70 degrees
    results, pixels = [], {}
    with tempfile.TemporaryDirectory() as tmp:
        for node in ("metallic", "principled"):
            for d, n2, n3 in FILMS:
                px = render(sc, sphere, material(node, d, n2, n3), tmp)
                pixels[node, d, n2, n3] = px
                entry = {
                    "node": node,
                    "film_d": d,
                    "film_ior": n2,
                    "base_ior": n3,
                    "angles": compare(px, d, n2, n3, r),
                }
                if d > 0.0:
                    # The same node without the film: does the film act?
                    bare = render(sc, sphere, material(node, 0.0, n2, n3), tmp)
                    entry["film_changes_pixels_by"] = float(np.abs(px - bare)[inside].max())
                results.append(entry)
                print(
                    f"{node:10s} d {d:6.1f} n2 {n2:4.2f} n3 {n3:4.2f}: max |Cycles - ours| "
                    f"to 60 deg {worst(entry, 'max_deviation', 60):.4f}, to 70 deg "
                    f"{worst(entry, 'max_deviation', 70):.4f}",
                    file=sys.stderr,
                )
        # Render noise: a film again with another seed.
        d, n2, n3 = NOISE_FILM
        sc.cycles.seed = 2
        again = render(sc, sphere, material("metallic", d, n2, n3), tmp)
        sc.cycles.seed = 1
    noise = float(np.abs(again - pixels["metallic", d, n2, n3])[inside].max())
    nodes = float(
        max(
            np.abs(pixels["metallic", *f] - pixels["principled", *f])[inside].max()
            for f in FILMS
        )
    )
    films = [e for e in results if e["film_d"] > 0.0]
    plain = [e for e in results if e["film_d"] == 0.0]
    summary = {
        "max_deviation_to_60_deg": max(worst(e, "max_deviation", 60) for e in films),
        "max_deviation_to_70_deg": max(worst(e, "max_deviation", 70) for e in films),
        "max_deviation_plain_to_70_deg": max(worst(e, "max_deviation", 70) for e in plain),
        "seed_difference": noise,
        "principled_minus_metallic": nodes,
    }
    print(json.dumps(summary), file=sys.stderr)
    OUT.parent.mkdir(exist_ok=True)
    meta = {
        "blender": bpy.app.version_string,
        "resolution": RES,
        "samples": SAMPLES,
        "view_transform": sc.view_settings.view_transform,
        "summary": summary,
        "films": results,
    }
    OUT.write_text(json.dumps(meta, indent=1) + "\n")


if __name__ == "__main__":
    main()
