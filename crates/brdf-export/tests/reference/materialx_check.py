"""Validate MaterialX documents with MaterialX's own Document.validate()
against its standard data libraries (pip install materialx); print, per
file, its text and (valid, message) as JSON."""

import json
import sys

import MaterialX as mx


def main():
    lib = mx.createDocument()
    mx.loadLibraries(mx.getDefaultDataLibraryFolders(), mx.getDefaultDataSearchPath(), lib)
    out = []
    for f in sys.argv[1:]:
        doc = mx.createDocument()
        text = open(f).read()
        mx.readFromXmlString(doc, text)
        doc.importLibrary(lib)
        valid, message = doc.validate()
        nodes = [n for n in doc.getNodes() if n.getType() == "surfaceshader"]
        shaders = [n.getCategory() for n in nodes]
        # Inputs the shader's node definition does not declare.
        unknown = [f"{n.getCategory()}.{i.getName()}" for n in nodes for i in n.getInputs()
                   if n.getNodeDef() is None or n.getNodeDef().getActiveInput(i.getName()) is None]
        out.append({"file": f, "text": text, "materialx": mx.getVersionString(),
                    "valid": valid, "message": message, "shaders": shaders,
                    "unknown_inputs": unknown})
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
