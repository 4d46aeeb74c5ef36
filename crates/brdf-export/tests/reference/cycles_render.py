"""Render exported materials in Blender Cycles (pip bpy, CPU) in the judge
scene of docs/appearance.md, studio light set, and write linear
radiance EXRs for render_check.py to compare with brdf-render.

  python cycles_render.py OUT_DIR [--spp N] [--antialias] FILE...   (with bpy)

--antialias: Cycles' Gaussian pixel filter (width 1.5 px) instead of rays
through the pixel centres, for pictures (results/renderers/), not checks.

FILE is loaded the way a Blender user loads it:
  *.py    the `brdf export --to blender` script, run (its build() makes the
          material: Principled BSDF, single-scatter GGX)
  *.usda  Blender's USD importer (UsdPreviewSurface -> Principled BSDF,
          `import_all_materials`, the file binds nothing); usd-core has no
          renderer, Cycles is the USD route here
  *.gltf  Blender's glTF importer (io_scene_gltf2, glTF material ->
          Principled BSDF); the asset has a material and no mesh, which the
          importer skips, so a copy with one triangle using material 0 is
          imported (the material itself untouched)
and put on the sphere. OUT_DIR/NAME.studio.seed2.exr and .seed3.exr (two
seeds, for the noise floor) are written per file
(NAME = the file name with `.` for `/`), plus OUT_DIR/cycles.json: Blender's
version, the settings, the Principled BSDF each file became (distribution,
inputs) and a units check: the key light and the surround seen directly by
the camera, whose pixel values must be the radiances of the scene (12, 0.05).

The scene (docs/appearance.md):
  - sphere: radius 1 at the origin, a true sphere (a one-point point cloud
    of radius 1, which Cycles intersects analytically; no facets);
  - camera: at (0, 0, 6) looking down -z, up +y, 22 deg field of view,
    128 x 128; pixel filter width 0.01 px, i.e. rays through the pixel
    centres, as brdf-render's;
  - studio light: world background of constant radiance 0.05 (strength 1,
    colour 0.05), and a 1.2 x 1.2 quad with an Emission shader of colour
    1, strength 12 (Cycles: an emission shader of strength S and colour C
    on a surface has radiance S * C; checked by the units render) at
    (3, 3, 4) facing the origin, placed as Mitsuba's rectangle
    (look_at then scale 0.6);
  - direct light only (max bounces 0: the sphere is convex), no clamping,
    no denoising, light tree off, fixed seed;
  - colour: the Linear Rec.709 working space (linear sRGB, as the fits),
    view transform Standard, look None, exposure 0, gamma 1; the EXR holds
    scene-linear radiance.
"""

import base64
import json
import math
import os
import runpy
import sys
import tempfile

import bpy
import numpy as np

SIZE = 128
FOV_DEG = 22.0


def look_at(origin, target, up):
    """Mitsuba's look_at: columns (x, y, z) of the rotation, z toward target."""
    origin, target, up = (np.asarray(a, float) for a in (origin, target, up))
    d = target - origin
    d /= np.linalg.norm(d)
    left = np.cross(up, d)
    left /= np.linalg.norm(left)
    new_up = np.cross(d, left)
    return left, new_up, d


def reset(spp, seed, antialias=False):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = seed
    c.max_bounces = 0
    c.diffuse_bounces = 0
    c.glossy_bounces = 0
    c.transmission_bounces = 0
    c.volume_bounces = 0
    c.transparent_max_bounces = 0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.use_light_tree = False
    if antialias:
        c.pixel_filter_type = "GAUSSIAN"
        c.filter_width = 1.5
    else:
        c.pixel_filter_type = "BOX"
        c.filter_width = 0.01
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    scene.render.resolution_x = SIZE
    scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    vs = scene.view_settings
    vs.view_transform = "Standard"
    vs.look = "None"
    vs.exposure = 0.0
    vs.gamma = 1.0
    im = scene.render.image_settings
    im.file_format = "OPEN_EXR"
    im.color_depth = "32"
    im.exr_codec = "ZIP"
    im.color_mode = "RGB"
    return scene


def camera(scene):
    cam = bpy.data.cameras.new("judge")
    cam.type = "PERSP"
    cam.sensor_fit = "HORIZONTAL"
    cam.angle = math.radians(FOV_DEG)
    cam.clip_start = 0.01
    cam.clip_end = 100.0
    obj = bpy.data.objects.new("judge", cam)
    obj.location = (0.0, 0.0, 6.0)
    obj.rotation_euler = (0.0, 0.0, 0.0)  # looks down -z, up +y
    scene.collection.objects.link(obj)
    scene.camera = obj
    return obj


def studio(scene):
    world = bpy.data.worlds.new("studio")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0.05, 0.05, 0.05, 1.0)
    bg.inputs["Strength"].default_value = 1.0
    scene.world = world
    # The key light: Mitsuba's rectangle [-1, 1]^2 (normal +z) under
    # look_at((3, 3, 4), origin, +y) @ scale(0.6).
    x, y, z = look_at([3, 3, 4], [0, 0, 0], [0, 1, 0])
    o = np.array([3.0, 3.0, 4.0])
    corners = [o + 0.6 * (a * x + b * y) for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    mesh = bpy.data.meshes.new("key")
    # Counter-clockwise seen from +z local: the face normal is z, toward the origin.
    mesh.from_pydata([tuple(c) for c in corners], [], [(0, 1, 2, 3)])
    mesh.update()
    n = np.array(mesh.polygons[0].normal)
    assert np.dot(n, z) > 0.999, (n, z)
    mat = bpy.data.materials.new("key")
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    em = nodes.new("ShaderNodeEmission")
    em.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    em.inputs["Strength"].default_value = 12.0
    out = nodes.new("ShaderNodeOutputMaterial")
    mat.node_tree.links.new(em.outputs["Emission"], out.inputs["Surface"])
    # Mitsuba's rectangle emits on its front side only.
    mat.cycles.emission_sampling = "FRONT"
    mesh.materials.append(mat)
    obj = bpy.data.objects.new("key", mesh)
    scene.collection.objects.link(obj)
    return obj


def sphere(scene, material):
    """A one-point point cloud of radius 1 (Cycles renders points as spheres)."""
    mesh = bpy.data.meshes.new("centre")
    mesh.from_pydata([(0.0, 0.0, 0.0)], [], [])
    mesh.update()
    obj = bpy.data.objects.new("sphere", mesh)
    scene.collection.objects.link(obj)
    tree = bpy.data.node_groups.new("to_sphere", "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    gin = tree.nodes.new("NodeGroupInput")
    gout = tree.nodes.new("NodeGroupOutput")
    pts = tree.nodes.new("GeometryNodeMeshToPoints")
    pts.inputs["Radius"].default_value = 1.0
    setm = tree.nodes.new("GeometryNodeSetMaterial")
    setm.inputs["Material"].default_value = material
    tree.links.new(gin.outputs[0], pts.inputs["Mesh"])
    tree.links.new(pts.outputs["Points"], setm.inputs["Geometry"])
    tree.links.new(setm.outputs["Geometry"], gout.inputs[0])
    mod = obj.modifiers.new("to_sphere", "NODES")
    mod.node_group = tree
    return obj


def render(scene, path):
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    w, h = img.size
    px = np.array(img.pixels[:], dtype=np.float32).reshape(h, w, img.channels)
    bpy.data.images.remove(img)
    return px[::-1, :, :3]  # Blender's rows run bottom to top


def principled_of(mat):
    nodes = [n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED"]
    if len(nodes) != 1:
        return {"principled_nodes": len(nodes)}
    n = nodes[0]
    inputs = {}
    for i in n.inputs:
        if i.is_linked or not hasattr(i, "default_value"):
            continue
        v = i.default_value
        if isinstance(v, float):
            inputs[i.name] = round(v, 6)
        elif hasattr(v, "__len__") and len(v) in (3, 4):
            inputs[i.name] = [round(float(x), 6) for x in v]
    linked = sorted(i.name for i in n.inputs if i.is_linked)
    return {"principled_nodes": 1, "distribution": n.distribution, "inputs": inputs, "linked_inputs": linked}


def with_triangle(path):
    """The glTF asset of `path` with one triangle (a data-URI buffer) using
    its material 0, so that the importer makes the material."""
    with open(path) as fh:
        g = json.load(fh)
    assert not g.get("meshes"), f"{path}: expected a material-only asset"
    pos = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype="<f4").tobytes()
    g["buffers"] = [{"byteLength": len(pos),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(pos).decode()}]
    g["bufferViews"] = [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)}]
    g["accessors"] = [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}]
    g["meshes"] = [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}]
    g["nodes"] = [{"mesh": 0}]
    g["scenes"] = [{"nodes": [0]}]
    g["scene"] = 0
    return g


def load_material(path):
    """The material `path` makes in Blender, loaded as a user loads it."""
    before = set(bpy.data.materials)
    if path.endswith(".py"):
        argv = sys.argv
        sys.argv = [path]
        try:
            g = runpy.run_path(path, run_name="exported")
            mat = g["build"]()
        finally:
            sys.argv = argv
        return mat, "script build()"
    if path.endswith(".usda") or path.endswith(".usd"):
        bpy.ops.wm.usd_import(filepath=os.path.abspath(path), import_all_materials=True)
        route = "wm.usd_import(import_all_materials=True)"
    elif path.endswith(".gltf"):
        with tempfile.TemporaryDirectory() as d:
            copy = os.path.join(d, os.path.basename(path))
            with open(copy, "w") as fh:
                json.dump(with_triangle(path), fh)
            bpy.ops.import_scene.gltf(filepath=copy)
        route = "import_scene.gltf (a triangle added to use the material)"
    else:
        raise ValueError(f"{path}: not a .py, .usda or .gltf export")
    new = [m for m in bpy.data.materials if m not in before and m.name != "key"]
    if len(new) != 1:
        raise RuntimeError(f"{path}: the importer made {len(new)} materials: {[m.name for m in new]}")
    # Imported objects (none for these files, but be safe) are removed.
    for o in list(bpy.context.scene.objects):
        if o.type not in ("CAMERA",) and o.name not in ("key", "judge"):
            bpy.data.objects.remove(o)
    return new[0], route


def units_check(out_dir, spp):
    """Render the key light and the surround straight into the camera."""
    scene = reset(spp, 1)
    studio(scene)
    cam = camera(scene)
    # From the origin, looking at the key light's centre.
    d = np.array([3.0, 3.0, 4.0]) / np.linalg.norm([3.0, 3.0, 4.0])
    cam.location = (0.0, 0.0, 0.0)
    cam.rotation_mode = "QUATERNION"
    from mathutils import Vector

    cam.rotation_quaternion = Vector((0.0, 0.0, -1.0)).rotation_difference(Vector(tuple(d)))
    cam.data.angle = math.radians(40.0)
    scene.render.resolution_x = scene.render.resolution_y = 16
    px = render(scene, os.path.join(out_dir, "units.exr"))
    os.remove(os.path.join(out_dir, "units.exr"))
    centre = px[7:9, 7:9].reshape(-1, 3).mean(axis=0)
    corner = px[0, 0]
    return {"key_radiance_seen": [round(float(v), 5) for v in centre],
            "surround_radiance_seen": [round(float(v), 5) for v in corner],
            "expected": {"key": 12.0, "surround": 0.05}}


def main():
    args = sys.argv[1:]
    spp = 256
    antialias = "--antialias" in args
    if antialias:
        args.remove("--antialias")
    if "--spp" in args:
        i = args.index("--spp")
        spp = int(args[i + 1])
        del args[i:i + 2]
    out_dir, files = args[0], args[1:]
    os.makedirs(out_dir, exist_ok=True)
    # Blender writes its own messages to file descriptor 1: send them to
    # stderr while it works.
    stdout = os.dup(1)
    os.dup2(2, 1)
    report = {"blender": bpy.app.version_string, "spp": spp, "size": SIZE, "light": "studio",
              "pixel_filter_width": 1.5 if antialias else 0.01, "max_bounces": 0, "view_transform": "Standard",
              "units": units_check(out_dir, 16), "files": []}
    for f in files:
        name = os.path.relpath(f).replace("/", ".")
        # Two seeds: the second render is the noise floor.
        for seed in (2, 3):
            scene = reset(spp, seed, antialias)
            camera(scene)
            studio(scene)
            mat, route = load_material(f)
            sphere(scene, mat)
            exr = os.path.join(out_dir, f"{name}.studio.seed{seed}.exr")
            px = render(scene, exr)
            if seed == 2:
                r = {"file": os.path.relpath(f), "route": route, "material": mat.name,
                     "exr": os.path.basename(exr), "finite": bool(np.isfinite(px).all()),
                     "mean": [float(v) for v in px.reshape(-1, 3).mean(axis=0)]}
                r.update(principled_of(mat))
        report["files"].append(r)
    sys.stdout.flush()
    os.dup2(stdout, 1)
    with open(os.path.join(out_dir, "cycles.json"), "w") as fh:
        json.dump(report, fh, indent=1)


if __name__ == "__main__":
    main()
