"""Cycles material of `lobes-conductor-cycles` written by `brdf export --to blender`: the model's terms as Diffuse, Glossy (GGX) and Metallic (GGX) BSDFs joined by Add Shader nodes, exact in Cycles.

Run: blender -b -P THIS.py [-- --blend OUT.blend], or python THIS.py [--blend OUT.blend] with bpy.
"""

import os
import sys

import bpy

NAME = "cc_ibiza_sunset_rgb"
# (node type, properties, inputs) of each term of the sum.
TERMS = [
    (
        "ShaderNodeBsdfDiffuse",
        {},
        {"Color": (0.00207024513736914, 0.0005469464684677171, 4.336808689942018e-17, 1.0), "Roughness": 0.0},
    ),
    (
        "ShaderNodeBsdfMetallic",
        {"distribution": "GGX", "fresnel_type": "PHYSICAL_CONDUCTOR"},
        {"IOR": (2.505405006878358, 1.2762676252099057, 2.0154839058440808), "Extinction": (1.6473606885866192, 0.7937423939677422, 0.0), "Roughness": 0.30744158027848517},
    ),
]


def build(name=NAME):
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    # Kept in a saved .blend without an object using it (a library material).
    mat.use_fake_user = True
    if mat.node_tree is None:
        # Blender before 5 makes a material's node tree only on request.
        mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    out.location = (300 * (len(TERMS) + 1), 0)
    total = None
    for i, (kind, props, inputs) in enumerate(TERMS):
        node = tree.nodes.new(kind)
        node.location = (300 * i, -250)
        for key, value in props.items():
            setattr(node, key, value)
        for key, value in inputs.items():
            node.inputs[key].default_value = value
        if total is None:
            total = node.outputs["BSDF"]
            continue
        # Add Shader sums its two closures exactly.
        add = tree.nodes.new("ShaderNodeAddShader")
        add.location = (300 * i + 150, 0)
        tree.links.new(total, add.inputs[0])
        tree.links.new(node.outputs["BSDF"], add.inputs[1])
        total = add.outputs["Shader"]
    tree.links.new(total, out.inputs["Surface"])
    return mat


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    build()
    if "--blend" in argv:
        i = argv.index("--blend")
        if i + 1 >= len(argv):
            sys.exit("--blend needs a file name: --blend OUT.blend")
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(argv[i + 1]))
