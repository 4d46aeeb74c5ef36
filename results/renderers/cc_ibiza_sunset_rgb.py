"""Cycles material of `film-cycles` written by `brdf export --to blender`: the model's terms as Diffuse, Glossy (GGX) and Metallic (GGX) BSDFs joined by Add Shader nodes, exact in Cycles.

Run: blender -b -P THIS.py [-- --blend OUT.blend], or python THIS.py [--blend OUT.blend] with bpy.
"""

import os
import sys

import bpy

NAME = "cc_ibiza_sunset_rgb"
# (node type, properties, inputs, weight) of each term of the sum.
TERMS = [
    (
        "ShaderNodeBsdfDiffuse",
        {},
        {"Color": (0.0014353215375011992, 0.0008316664905916535, 9.280770596475918e-17, 1.0), "Roughness": 0.0},
        None,
    ),
    (
        "ShaderNodeBsdfMetallic",
        {"distribution": "GGX", "fresnel_type": "PHYSICAL_CONDUCTOR"},
        {"IOR": (4.024093959762252, 4.024093959762252, 4.024093959762252), "Extinction": (0.0, 0.0, 0.0), "Roughness": 0.30736794372974163, "Thin Film Thickness": 150.09210465254557, "Thin Film IOR": 2.4984018892589903},
        0.9999999999999989,
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
    for i, (kind, props, inputs, weight) in enumerate(TERMS):
        node = tree.nodes.new(kind)
        node.location = (300 * i, -250)
        for key, value in props.items():
            setattr(node, key, value)
        for key, value in inputs.items():
            node.inputs[key].default_value = value
        term = node.outputs["BSDF"]
        if weight is not None:
            # Mix Shader is fac * B + (1 - fac) * A; with A unlinked it is
            # the term scaled by fac.
            mix = tree.nodes.new("ShaderNodeMixShader")
            mix.location = (300 * i + 75, -450)
            mix.inputs["Fac"].default_value = weight
            tree.links.new(term, mix.inputs[2])
            term = mix.outputs["Shader"]
        if total is None:
            total = term
            continue
        # Add Shader sums its two closures exactly.
        add = tree.nodes.new("ShaderNodeAddShader")
        add.location = (300 * i + 150, 0)
        tree.links.new(total, add.inputs[0])
        tree.links.new(term, add.inputs[1])
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
