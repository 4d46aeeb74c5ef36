"""Run every exported Blender script in Blender's Python module (pip bpy):
the script builds its material and saves a .blend (`--blend`); the .blend
is then opened again and the Principled BSDF's inputs read back. Prints,
per script, its text and what Blender holds as JSON.

Run: python blender_check.py paper_white/*.py (with bpy installed)."""

import json
import os
import runpy
import sys
import tempfile

import bpy


def read_back(blend, name):
    bpy.ops.wm.open_mainfile(filepath=blend)
    mat = bpy.data.materials[name]
    nodes = [n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED"]
    outs = [n for n in mat.node_tree.nodes if n.type == "OUTPUT_MATERIAL"]
    linked = bool(outs) and outs[0].inputs["Surface"].is_linked
    n = nodes[0]
    values = {}
    for i in n.inputs:
        if i.name in ("Base Color", "Metallic", "Roughness", "IOR", "Specular IOR Level",
                      "Specular Tint", "Coat Weight", "Coat Roughness", "Coat IOR"):
            v = i.default_value
            values[i.name] = round(v, 6) if isinstance(v, float) else [round(x, 6) for x in v]
    return {"material": mat.name, "principled_nodes": len(nodes), "surface_linked": linked,
            "distribution": n.distribution, "inputs": values}


def main():
    # Blender writes its own messages to file descriptor 1: send them to
    # stderr while it works, so stdout holds only the JSON.
    stdout = os.dup(1)
    os.dup2(2, 1)
    out = []
    for f in sys.argv[1:]:
        text = open(f).read()
        with tempfile.TemporaryDirectory() as d:
            blend = os.path.join(d, "m.blend")
            bpy.ops.wm.read_factory_settings(use_empty=True)
            argv = sys.argv
            sys.argv = [f, "--blend", blend]
            g = runpy.run_path(f, run_name="__main__")
            sys.argv = argv
            r = {"file": f, "text": text, "blender": bpy.app.version_string,
                 "blend_written": os.path.getsize(blend) > 0}
            r.update(read_back(blend, g["NAME"]))
            # What the script meant to set, to compare in the Rust test.
            r["expected"] = {k: (round(float(v), 6) if isinstance(v, (int, float)) else [round(float(x), 6) for x in v])
                             for k, v in g["INPUTS"].items()}
        out.append(r)
    sys.stdout.flush()
    os.dup2(stdout, 1)
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
