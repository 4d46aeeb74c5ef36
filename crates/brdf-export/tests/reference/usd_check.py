"""Open every exported `.usda` with USD itself (pip usd-core) and check it
is a referencing-ready material: the layer's default prim is a
`UsdShade.Material` whose surface output is connected to a `Shader` with
`info:id = UsdPreviewSurface`, and every input the shader sets is one of
the UsdPreviewSurface inputs (the specification's table, and Sdr's node
definition where the usdShaders plugin is present) with its type. Prints,
per file, its text and the findings as JSON."""

import json
import sys

from pxr import Sdf, Usd, UsdShade

# UsdPreviewSurface inputs and their types (UsdPreviewSurface specification).
PREVIEW_INPUTS = {
    "diffuseColor": "color3f", "emissiveColor": "color3f", "useSpecularWorkflow": "int",
    "specularColor": "color3f", "metallic": "float", "roughness": "float",
    "clearcoat": "float", "clearcoatRoughness": "float", "opacity": "float",
    "opacityMode": "token", "opacityThreshold": "float", "ior": "float",
    "normal": "normal3f", "displacement": "float", "occlusion": "float",
}


def sdr_inputs():
    try:
        from pxr import Sdr
        node = Sdr.Registry().GetShaderNodeByIdentifier("UsdPreviewSurface")
        return sorted(node.GetInputNames()) if node else None
    except Exception:  # usd-core without the usdShaders plugin
        return None


def check(path):
    stage = Usd.Stage.Open(path)
    prim = stage.GetDefaultPrim()
    problems = []
    if not prim or not prim.IsA(UsdShade.Material):
        return {"valid": False, "problems": ["the default prim is not a Material"]}
    material = UsdShade.Material(prim)
    source = material.ComputeSurfaceSource()
    shader = source[0] if source and source[0] else None
    if shader is None:
        return {"valid": False, "problems": ["the surface output is not connected"]}
    shader_id = shader.GetIdAttr().Get()
    if shader_id != "UsdPreviewSurface":
        problems.append(f"shader id {shader_id}")
    sdr = sdr_inputs()
    inputs = {}
    for i in shader.GetInputs():
        name, kind = i.GetBaseName(), str(i.GetTypeName())
        inputs[name] = i.Get() if kind in ("int", "float") else list(i.Get())
        if PREVIEW_INPUTS.get(name) != kind:
            problems.append(f"input {name} ({kind}) is not a UsdPreviewSurface input")
        if sdr is not None and name not in sdr:
            problems.append(f"input {name} unknown to Sdr")
    return {"valid": not problems, "problems": problems, "material": str(prim.GetPath()),
            "shader": shader_id, "inputs": inputs, "sdr_checked": sdr is not None}


def main():
    from pxr import Usd as _u
    out = []
    for f in sys.argv[1:]:
        r = {"file": f, "text": open(f).read(), "usd": ".".join(map(str, _u.GetVersion()))}
        r.update(check(f))
        out.append(r)
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
