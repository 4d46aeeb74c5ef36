"""Principled BSDF material written by `brdf export --to blender`.

Run: blender -b -P THIS.py [-- --blend OUT.blend], or python THIS.py [--blend OUT.blend] with bpy.
"""

import os
import sys

import bpy

NAME = "colodur_napoli_4f_rgb"
INPUTS = {
    "Base Color": (0.23964080916186964, 0.03755564212157061, 0.04274733449672505, 1.0),
    "Metallic": 0.0,
    "Roughness": 0.712403651607217,
    "IOR": 1.5,
    "Specular IOR Level": 0.5,
}


def build(name=NAME):
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    # Kept in a saved .blend without an object using it (a library material).
    mat.use_fake_user = True
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
