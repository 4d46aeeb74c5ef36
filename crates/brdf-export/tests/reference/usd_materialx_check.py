"""Check each USD layer of a MaterialX graph (`M.usda`) against the
MaterialX document of the same fit beside it (`M.mtlx`, the one MaterialX's
GLSL renderer renders in lobes_check.sh), with USD (pip usd-core) reading
the layer and MaterialX (pip materialx) reading the document and its
standard library:

- the layer's default prim is a `UsdShade.Material` whose `mtlx` surface
  output is connected to the shader MaterialX's `surfacematerial` names;
- every MaterialX node has a `Shader` prim of its name whose `info:id` is
  the node definition MaterialX itself resolves for the node;
- every input of the node is an input of the prim, of the USD type of the
  node definition's input type (MaterialX's USD type table: color3 as
  color3f, vector2 as float2, float, string; BSDF and surfaceshader links
  as token connections), with the same value (to 1e-12, relative) or a
  connection to the same node's `outputs:out`;
- the prim has no input the node lacks.

Prints, per file, its text and the findings as JSON."""

import json
import os
import sys

import MaterialX as mx
from pxr import Usd, UsdShade

USD_TYPE = {"color3": "color3f", "vector2": "float2", "float": "float", "string": "string",
            "BSDF": "token", "surfaceshader": "token"}


def values_equal(usd_value, mtlx_value):
    if isinstance(mtlx_value, str):
        return usd_value == mtlx_value
    a = list(usd_value) if hasattr(usd_value, "__len__") else [usd_value]
    b = list(mtlx_value) if hasattr(mtlx_value, "__len__") else [mtlx_value]
    return len(a) == len(b) and all(abs(x - y) <= 1e-12 * max(1.0, abs(y)) for x, y in zip(a, b))


def check_node(node, prim, problems):
    nodedef = node.getNodeDef()
    if nodedef is None:
        problems.append(f"{node.getName()}: MaterialX resolves no node definition")
        return
    shader = UsdShade.Shader(prim)
    if shader.GetIdAttr().Get() != nodedef.getName():
        problems.append(f"{node.getName()}: info:id {shader.GetIdAttr().Get()}, "
                        f"MaterialX's definition {nodedef.getName()}")
    names = set()
    for inp in node.getInputs():
        name = inp.getName()
        names.add(name)
        usd_input = shader.GetInput(name)
        want = USD_TYPE.get(nodedef.getActiveInput(name).getType())
        if not usd_input:
            problems.append(f"{node.getName()}.{name}: missing")
            continue
        if str(usd_input.GetTypeName()) != want:
            problems.append(f"{node.getName()}.{name}: type {usd_input.GetTypeName()}, want {want}")
        if inp.getNodeName():
            sources = usd_input.GetConnectedSources()[0]
            source = sources[0].source.GetPath().name if sources else None
            output = sources[0].sourceName if sources else None
            if (source, output) != (inp.getNodeName(), "out"):
                problems.append(f"{node.getName()}.{name}: connected to {source}.{output}, "
                                f"want {inp.getNodeName()}.out")
        elif not values_equal(usd_input.Get(), inp.getValue()):
            problems.append(f"{node.getName()}.{name}: {usd_input.Get()} != {inp.getValue()}")
    extra = {i.GetBaseName() for i in shader.GetInputs()} - names
    if extra:
        problems.append(f"{node.getName()}: inputs {sorted(extra)} not in the document")


def check(usda, mtlx):
    doc = mx.createDocument()
    mx.readFromXmlFile(doc, mtlx)
    lib = mx.createDocument()
    mx.loadLibraries(mx.getDefaultDataLibraryFolders(), mx.getDefaultDataSearchPath(), lib)
    doc.importLibrary(lib)
    stage = Usd.Stage.Open(usda)
    prim = stage.GetDefaultPrim()
    if not prim or not prim.IsA(UsdShade.Material):
        return {"valid": False, "problems": ["the default prim is not a Material"]}
    problems = []
    material = doc.getMaterialNodes()[0]
    shader_name = material.getInput("surfaceshader").getNodeName()
    source = UsdShade.Material(prim).ComputeSurfaceSource("mtlx")[0]
    if not source or source.GetPath().name != shader_name:
        problems.append(f"mtlx:surface is connected to {source and source.GetPath()}, "
                        f"want {shader_name}")
    checked = []
    for node in doc.getNodes():
        if node.getCategory() == "surfacematerial":
            continue
        child = prim.GetChild(node.getName())
        if not child:
            problems.append(f"{node.getName()}: no prim")
            continue
        check_node(node, child, problems)
        checked.append(node.getNodeDef().getName() if node.getNodeDef() else None)
    return {"valid": not problems, "problems": problems, "material": str(prim.GetPath()),
            "node_definitions": checked}


def main():
    out = []
    for f in sys.argv[1:]:
        mtlx = os.path.splitext(f)[0] + ".mtlx"
        r = {"file": f, "text": open(f).read(), "usd": ".".join(map(str, Usd.GetVersion())),
             "materialx": mx.getVersionString()}
        r.update(check(f, mtlx))
        out.append(r)
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
