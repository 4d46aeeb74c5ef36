"""Principled BSDF material written by `brdf export --to blender`.

Run: blender -b -P THIS.py [-- --blend OUT.blend], or python THIS.py [--blend OUT.blend] with bpy.

converted by fitting: `ggx` has no exact equivalent here, so `gltf` was fitted to its values at 2048 direction pairs up to 80 deg; Ngan L2 1.5352e-2 1/sr, relative L2 6.9209e-2; image error at 128 px: HDR-FLIP sky 0.0124, studio 0.0122 (mean 0.0123), mean-colour CIEDE2000 at most 0.03
"""

import os
import sys

import bpy

NAME = "paper_white_rgb"
INPUTS = {
    "Base Color": (0.8397799100939681, 0.8525694281846694, 1, 1.0),
    "Metallic": 0.08680115304302052,
    "Roughness": 0.682254762882041,
    "IOR": 1.5,
    "Specular IOR Level": 0.5,
}


def build(name=NAME):
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    # Kept in a saved .blend without an object using it (a library material).
    mat.use_fake_user = True
    if mat.node_tree is None:
        # Blender before 5 makes a material's node tree only on request
        # (`use_nodes`, deprecated in Blender 5, where every material has one).
        mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    out = nodes.new("ShaderNodeOutputMaterial")
    out.location = (300, 0)
    mat.node_tree.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    # Single-scatter GGX, as glTF's (MULTI_GGX would add multiple scattering).
    bsdf.distribution = "GGX"
    for key, value in INPUTS.items():
        bsdf.inputs[key].default_value = value
    return mat


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    build()
    if "--blend" in argv:
        i = argv.index("--blend")
        if i + 1 >= len(argv):
            sys.exit("--blend needs a file name: --blend OUT.blend")
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(argv[i + 1]))
