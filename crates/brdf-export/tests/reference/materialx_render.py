"""Render MaterialX documents in MaterialX's own GLSL renderer (pip
`materialx`: MaterialX.PyMaterialXRenderGlsl, an OpenGL 4 context; Mesa's
llvmpipe under Xvfb serves without a GPU) in the judge scene of
docs/appearance.md, studio light set, and write linear radiance EXRs
for render_check.py to compare with brdf-render.

  xvfb-run -a python materialx_render.py OUT_DIR FILE.mtlx...
  xvfb-run -a python materialx_render.py --probe   (exits 0 if an OpenGL context can be made)

Each document is loaded with MaterialX's standard data libraries, GLSL is
generated for its material (MaterialX's own shading graphs: `gltf_pbr`,
`standard_surface`, `open_pbr_surface`) and drawn on the sphere.
OUT_DIR/NAME.studio.seed2.exr and .seed3.exr are written per file (NAME = the
file name with `.` for `/`): the renderer has no seed, so the second is an
independent rerun (a fresh program), whose difference from the first is the
renderer's floor (0 when it is deterministic); for a `gltf_pbr` document
also NAME.studio.gltf_spec.exr, drawn with the glTF spec's formulas put back
into MaterialX's GLSL (materialx_gltf_spec.py: the diagnosis of what
differs); plus OUT_DIR/materialx.json: MaterialX's version, the settings,
the shader node of each file and its mean radiance.

The scene, as brdf-render's (crates/brdf-render):
  - camera at (0, 0, 6) looking down -z, up +y, 22 deg field of view
    (perspective), 128 x 128; the film is brdf-render's (Mitsuba's): pixels
    shaded at their centre, the pixels the silhouette crosses at 4 x 4
    sub-pixel positions (rendered at 512 x 512, which places its pixel
    centres there), rays that miss seeing the surround, then the Gaussian at
    whole-pixel offsets (crates/brdf-render/src/film.rs); which rays hit is
    decided on the true sphere, as brdf-render does;
  - sphere: radius 1 at the origin, a 512 x 256 latitude-longitude mesh whose
    normals are the sphere's, pushed out by 1 / cos^2(pi / 512) so that its
    faces cover every pixel whose ray hits the sphere (the shading points
    move by at most 4e-5), its faces behind z = 0 left out (never visible
    from the camera, and not shaded); the sub-pixel pass draws only its rim;
  - studio light: brdf-render's key light, the 1.2 x 1.2 square of radiance
    12 at (3, 3, 4) facing the origin, as its 8 x 8 cells
    (materialx_square_light.glsl, one light each); the constant surround of
    radiance 0.05 as MaterialX's environment light (uniform radiance and
    irradiance maps, filtered importance sampling with 64 samples: at most
    0.14 % from 1024 samples on the sphere's inner pixels);
  - no shadows, no ambient occlusion, no transparency; no colour transform
    (the documents are linear Rec.709, the working space); no sRGB encoding
    of the output.
"""

import ctypes
import json
import math
import os
import sys
import tempfile

import MaterialX as mx
import MaterialX.PyMaterialXGenGlsl as mx_gen_glsl
import MaterialX.PyMaterialXGenShader as mx_gen
import MaterialX.PyMaterialXRender as mx_render
import MaterialX.PyMaterialXRenderGlsl as mx_glsl
import numpy as np

import render_check as rc
from materialx_gltf_spec import patched_root

here = os.path.dirname(os.path.abspath(__file__))

SIZE = 128
SUB = 4  # brdf-render's SILHOUETTE_SAMPLES
FOV_DEG = 22.0
EYE = np.array([0.0, 0.0, 6.0])
KEY = {"origin": (3.0, 3.0, 4.0), "side": 1.2, "radiance": 12.0, "grid": 8}
SURROUND = 0.05
ENV_SAMPLES = 64
MESH = (512, 256)  # longitude, latitude segments
# The sub-pixel pass draws the sphere below this z only: seen from the camera
# it lies beyond 51.8 px from the centre, the silhouette's pixels beyond 54.
RIM_Z = 0.5
LIGHT_NODE = "judge_square_cell"
LIGHT_IMPL = "IM_point_light_genglsl"


def libraries(root):
    """The standard libraries under `root` (a search path holding
    `libraries/`) plus the square light's cell."""
    lib = mx.createDocument()
    mx.loadLibraries(mx.getDefaultDataLibraryFolders(), root, lib)
    nd = lib.addNodeDef("ND_" + LIGHT_NODE, "lightshader", LIGHT_NODE)
    nd.setNodeGroup("light")
    nd.addInput("position", "vector3")
    nd.addInput("facing", "vector3")
    nd.addInput("color", "color3")
    # MaterialX 1.39's GLSL generator makes a light shader (called with the
    # light's data) only of the implementations it registers by name in C++
    # (IM_point_light_genglsl, ...); any other name is emitted as an ordinary
    # node. The cell therefore takes over the point light's implementation
    # name (MaterialX's point_light is not used here).
    lib.removeImplementation(LIGHT_IMPL)
    impl = lib.addImplementation(LIGHT_IMPL)
    impl.setNodeDef(nd)
    impl.setFile("materialx_square_light.glsl")
    impl.setFunction("mx_" + LIGHT_NODE)
    impl.setTarget("genglsl")
    return lib


def key_cells():
    """(centre, facing, radiance x cell area) of each cell of the key light,
    placed as crates/brdf-render/src/area_light.rs places them."""
    o = np.array(KEY["origin"])
    n = -o / np.linalg.norm(o)
    u = np.cross([0.0, 1.0, 0.0], n)
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    g, side = KEY["grid"], KEY["side"]
    power = KEY["radiance"] * side * side / (g * g)
    cells = []
    for i in range(g):
        for j in range(g):
            a = ((i + 0.5) / g - 0.5) * side
            b = ((j + 0.5) / g - 0.5) * side
            cells.append((o + a * u + b * v, n, power))
    return cells


def light_handler(lib, contexts):
    """The key light's cells as lights (bound in each generator context),
    the surround as the environment."""
    doc = mx.createDocument()
    doc.importLibrary(lib)
    nodes = []
    for k, (q, n, power) in enumerate(key_cells()):
        node = doc.addNode(LIGHT_NODE, f"key_cell_{k}", "lightshader")
        node.setInputValue("position", mx.Vector3(*map(float, q)))
        node.setInputValue("facing", mx.Vector3(*map(float, n)))
        node.setInputValue("color", mx.Color3(power, power, power))
        nodes.append(node)
    lh = mx_render.LightHandler.create()
    for context in contexts:
        lh.registerLights(doc, nodes, context)
    lh.setLightSources(nodes)
    env = mx_render.createUniformImage(16, 8, 4, mx_render.BaseType.FLOAT,
                                       mx.Color4(SURROUND, SURROUND, SURROUND, 1.0))
    lh.setEnvRadianceMap(env)
    lh.setEnvIrradianceMap(env)
    lh.setEnvSampleCount(ENV_SAMPLES)
    # The light nodes live in `doc`, which the caller keeps while rendering.
    return lh, doc


def sphere_obj(path, z_max=math.inf):
    """A latitude-longitude unit sphere as OBJ, pushed out so that its faces
    lie outside the sphere (they then cover its whole silhouette); only the
    faces reaching below z = z_max."""
    n_lon, n_lat = MESH
    scale = 1.0 / (math.cos(math.pi / n_lon) * math.cos(math.pi / (2 * n_lat)))
    theta = np.linspace(0.0, math.pi, n_lat + 1)
    phi = np.linspace(0.0, 2.0 * math.pi, n_lon + 1)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    nrm = np.stack([np.sin(t) * np.cos(p), np.cos(t), -np.sin(t) * np.sin(p)], -1).reshape(-1, 3)
    uv = np.stack([p / (2 * math.pi), 1.0 - t / math.pi], -1).reshape(-1, 2)
    idx = np.arange((n_lat + 1) * (n_lon + 1)).reshape(n_lat + 1, n_lon + 1) + 1
    a, b, c, d = idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]
    tris = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    # The camera at z = 6 sees the unit sphere only where z > 1/6: faces
    # wholly behind z = 0 are never visible, and left out they are never
    # shaded (the renderer has no back-face culling; drawn, they were
    # shaded wherever no front face covered them first, which in the rim
    # pass is the whole inner disc).
    z = nrm[tris - 1, 2]
    tris = tris[(z.min(axis=1) < z_max) & (z.max(axis=1) > 0.0)]
    with open(path, "w") as fh:
        fh.write("".join(f"v {x:.9f} {y:.9f} {z:.9f}\n" for x, y, z in nrm * scale))
        fh.write("".join(f"vn {x:.9f} {y:.9f} {z:.9f}\n" for x, y, z in nrm))
        fh.write("".join(f"vt {s:.9f} {r:.9f}\n" for s, r in uv))
        fh.write("".join(f"f {i}/{i}/{i} {j}/{j}/{j} {k}/{k}/{k}\n" for i, j, k in tris))


def camera(size):
    cam = mx_render.Camera.create()
    cam.setViewMatrix(mx_render.Camera.createViewMatrix(mx.Vector3(*EYE), mx.Vector3(0, 0, 0), mx.Vector3(0, 1, 0)))
    near, far = 1.0, 20.0
    h = near * math.tan(math.radians(FOV_DEG) / 2)
    cam.setProjectionMatrix(mx_render.Camera.createPerspectiveMatrix(-h, h, -h, h, near, far))
    cam.setViewportSize(mx.Vector2(size, size))
    return cam


def generator(root):
    """The GLSL generator and its context with the scene's options, its
    sources under `root`."""
    gen = mx_gen_glsl.GlslShaderGenerator.create()
    context = mx_gen.GenContext(gen)
    search = mx.FileSearchPath(root.asString())
    search.append(mx.FilePath(here))
    context.registerSourceCodeSearchPath(search)
    opts = context.getOptions()
    opts.hwSpecularEnvironmentMethod = mx_gen.HwSpecularEnvironmentMethod.SPECULAR_ENVIRONMENT_FIS
    opts.hwMaxActiveLightSources = KEY["grid"] ** 2
    opts.hwShadowMap = False
    opts.hwAmbientOcclusion = False
    opts.hwTransparency = False
    opts.hwSrgbEncodeOutput = False
    opts.targetColorSpaceOverride = "lin_rec709"
    return gen, context


def renderer(lh):
    """One GLSL renderer with the lights (one OpenGL context: the
    environment maps are textures of the context that first binds them)."""
    r = mx_glsl.GlslRenderer.create(SIZE, SIZE, mx_render.BaseType.FLOAT)
    r.initialize()
    r.setImageHandler(mx_glsl.GLTextureHandler.create(mx_render.StbImageLoader.create()))
    r.setLightHandler(lh)
    return r


def meshes(tmp):
    """The geometry of each pass: the sphere for the pixel centres, its rim
    for the sub-pixel positions (only the silhouette's pixels use them)."""
    out = {}
    for size, name, z_max in ((SIZE, "sphere", math.inf), (SIZE * SUB, "rim", RIM_Z)):
        obj = os.path.join(tmp, f"{name}.obj")
        sphere_obj(obj, z_max)
        gh = mx_render.GeometryHandler.create()
        gh.addLoader(mx_render.TinyObjLoader.create())
        if not gh.loadGeometry(mx.FilePath(obj), False):
            raise RuntimeError(f"{obj}: MaterialX's OBJ loader did not load the sphere")
        out[size] = gh
    return out


def draw(r, shader, size, geometry):
    """One render of `shader` at size x size, rows top to bottom, RGB."""
    r.setGeometryHandler(geometry[size])
    r.setSize(size, size)
    r.setCamera(camera(size))
    r.createProgram(shader)
    r.validateInputs()
    r.render()
    img = r.captureImage(None)
    if img.getBaseType() != mx_render.BaseType.FLOAT or img.getChannelCount() != 4:
        raise RuntimeError("MaterialX's renderer did not return a float RGBA image")
    # The pixels are read from the image's buffer (as float32 RGBA rows);
    # copied before the image goes.
    buf = (ctypes.c_float * (size * size * 4)).from_address(img.getResourceBuffer())
    px = np.ctypeslib.as_array(buf).astype(np.float64).reshape(size, size, 4)
    return px[::-1, :, :3]  # OpenGL's rows run bottom to top


def hits(size):
    """Whether the ray through each pixel centre of a size x size film hits
    the unit sphere (brdf-render's camera and intersection)."""
    t = math.tan(math.radians(FOV_DEG) / 2)
    c = (np.arange(size) + 0.5) / size * 2.0 - 1.0
    x, y = np.meshgrid(c * t, -c * t)
    d = np.stack([x, y, -np.ones_like(x)], -1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    b = d @ EYE
    return b * b - (EYE @ EYE - 1.0) >= 0.0


def gaussian(img):
    """brdf-render's film filter: Mitsuba's Gaussian (sd 0.5 px, radius 2 px)
    at whole-pixel offsets, normalised by the weights inside the image."""
    taps = [(d, math.exp(-2.0 * d * d) - math.exp(-8.0)) for d in (-1, 0, 1)]
    for axis in (1, 0):
        acc, norm = np.zeros_like(img), np.zeros(img.shape[:2] + (1,))
        n = img.shape[axis]
        for d, k in taps:
            src = [slice(None)] * 2
            dst = [slice(None)] * 2
            src[axis], dst[axis] = slice(max(d, 0), n + min(d, 0)), slice(max(-d, 0), n - max(d, 0))
            acc[tuple(dst)] += k * img[tuple(src)]
            norm[tuple(dst)] += k
        img = acc / norm
    return img


def film(centre, sub):
    """brdf-render's film from the renders at pixel centres and at 4 x 4
    sub-pixel positions: the surround where rays miss the sphere."""
    hc, hs = hits(SIZE), hits(SIZE * SUB)
    sub = np.where(hs[..., None], sub, SURROUND)
    blocks = sub.reshape(SIZE, SUB, SIZE, SUB, 3).mean(axis=(1, 3))
    all_hit = hs.reshape(SIZE, SUB, SIZE, SUB).all(axis=(1, 3))
    none_hit = ~hs.reshape(SIZE, SUB, SIZE, SUB).any(axis=(1, 3))
    img = np.where((hc & all_hit)[..., None], centre, blocks)
    img = np.where((~hc & none_hit)[..., None], SURROUND, img)
    return gaussian(img)


def material_shader(path, lib, gen, context):
    """GLSL generated for the one material of the document at `path`."""
    doc = mx.createDocument()
    mx.readFromXmlFile(doc, path)
    doc.importLibrary(lib)
    valid, message = doc.validate()
    if not valid:
        raise RuntimeError(f"{path}: not a valid MaterialX document: {message}")
    materials = mx_gen.findRenderableElements(doc)
    if len(materials) != 1:
        raise RuntimeError(f"{path}: expected one material, found {len(materials)}")
    m = materials[0]
    shaders = [n for n in doc.getNodes() if n.getType() == "surfaceshader"]
    node = shaders[0].getCategory() if len(shaders) == 1 else None
    # Through the generator itself: context.getShaderGenerator() hands Python
    # a copy of the base class, whose generate() returns None.
    return gen.generate(m.getName(), m, context), m.getName(), node


def settings():
    """The scene and renderer settings, for materialx.json."""
    return {"materialx": mx.getVersionString(), "size": SIZE, "light": "studio",
            "camera": {"origin": list(EYE), "fov_deg": FOV_DEG, "projection": "perspective"},
            "film": f"brdf-render's: pixel centres, {SUB} x {SUB} sub-pixel positions on the silhouette, "
                    "Gaussian sd 0.5 px at whole-pixel offsets",
            "key_light": dict(KEY, cells_as="materialx_square_light.glsl"),
            "surround": {"radiance": SURROUND, "as": "environment light (uniform maps)",
                         "specular_environment": "FIS", "samples": ENV_SAMPLES},
            "sphere_mesh": {"longitude": MESH[0], "latitude": MESH[1]}}


def render_file(f, r, geometry, tools, out_dir):
    """Render the document `f` (twice; a `gltf_pbr` one also with the glTF
    spec's formulas) and write the EXRs; its entry of materialx.json."""
    name = os.path.relpath(f).replace("/", ".")
    shader, material, node = material_shader(f, *tools["materialx"])
    runs = [("seed2", shader), ("seed3", shader)]
    if node == "gltf_pbr":
        runs.append(("gltf_spec", material_shader(f, *tools["gltf_spec"])[0]))
    entry = {"file": os.path.relpath(f), "material": material, "shader_node": node}
    for tag, sh in runs:
        img = film(draw(r, sh, SIZE, geometry), draw(r, sh, SIZE * SUB, geometry))
        exr = os.path.join(out_dir, f"{name}.studio.{tag}.exr")
        rc.write_exr(exr, img)
        entry[tag] = {"exr": os.path.basename(exr), "finite": bool(np.isfinite(img).all()),
                      "mean": [float(v) for v in img.reshape(-1, 3).mean(axis=0)]}
    return entry


def main():
    if sys.argv[1:] == ["--probe"]:
        # Whether an OpenGL context can be made here (MaterialX's renderer
        # ends the process when it cannot open the X display).
        mx_glsl.GlslRenderer.create(8, 8, mx_render.BaseType.FLOAT).initialize()
        return
    out_dir, files = sys.argv[1], sys.argv[2:]
    os.makedirs(out_dir, exist_ok=True)
    report = dict(settings(), files=[])
    with tempfile.TemporaryDirectory() as tmp:
        tools = {}
        for kind, root in (("materialx", mx.getDefaultDataSearchPath()), ("gltf_spec", patched_root(tmp))):
            lib = libraries(root)
            tools[kind] = (lib, *generator(root))
        lh, _lights_doc = light_handler(tools["materialx"][0], [t[2] for t in tools.values()])
        r, geometry = renderer(lh), meshes(tmp)
        # The renderer has no seed: seed3 is a rerun from a fresh program.
        report["files"] = [render_file(f, r, geometry, tools, out_dir) for f in files]
    with open(os.path.join(out_dir, "materialx.json"), "w") as fh:
        json.dump(report, fh, indent=1)


if __name__ == "__main__":
    main()
