"""MaterialX's GLSL libraries with their two departures from the glTF 2.0
specification's BRDF (Appendix B, which brdf-render's `gltf` model is)
undone, for the diagnosis in materialx_render.py: rendered with these, a
`gltf_pbr` document must match brdf-render up to the scene's own
differences, which shows that the rest of MaterialX's difference is its
shading by construction, not the export.

The departures (MaterialX 1.39, libraries/pbrlib/genglsl):
  - the GGX lobes are scaled by Turquin's multiple-scattering compensation
    1 + F (1 - E(N.V)) / E(N.V) (lib/mx_microfacet_specular.glsl,
    mx_ggx_energy_compensation); the spec's lobe is single-scattering;
  - `gltf_pbr` layers the specular over the diffuse with MaterialX's `layer`,
    which weights the diffuse by 1 - E_spec(N.V), the specular lobe's
    directional albedo (albedo scaling; mx_generalized_schlick_bsdf.glsl);
    the spec's fresnel_mix weights it by 1 - F(V.H) for each light direction
    (brdf-render: 1 - max over channels).
Undone: the compensation returns 1, and for direct light the specular's
throughput is 1 - max F(V.H). The environment light keeps the albedo
scaling (its light comes from every direction at once).
"""

import os
import shutil

import MaterialX as mx

# (file under libraries/pbrlib/genglsl, MaterialX 1.39.5's text, replacement)
PATCHES = [
    ("lib/mx_microfacet_specular.glsl",
     "    return 1.0 + Fss * (1.0 - Ess) / Ess;\n",
     "    return vec3(1.0);\n"),
    ("mx_generalized_schlick_bsdf.glsl",
     "        vec3 dirAlbedo = mx_ggx_dir_albedo(NdotV, avgAlpha, safeColor0, safeColor90) * comp;\n"
     "        float avgDirAlbedo = dot(dirAlbedo, vec3(1.0 / 3.0));\n"
     "        bsdf.throughput = vec3(1.0 - avgDirAlbedo * weight);\n"
     "\n"
     "        // Note: NdotL is cancelled out\n",
     "        bsdf.throughput = vec3(1.0 - max(F.x, max(F.y, F.z)) * weight);\n"
     "\n"
     "        // Note: NdotL is cancelled out\n"),
]


def patched_root(tmp):
    """A search path under `tmp` holding a copy of MaterialX's libraries
    with PATCHES applied; fails if this MaterialX's sources differ."""
    src = mx.getDefaultDataSearchPath().find(mx.FilePath("libraries")).asString()
    dst = os.path.join(tmp, "libraries")
    shutil.copytree(src, dst)
    for rel, old, new in PATCHES:
        path = os.path.join(dst, "pbrlib", "genglsl", rel)
        with open(path) as fh:
            text = fh.read()
        if text.count(old) != 1:
            raise RuntimeError(f"{rel}: MaterialX {mx.getVersionString()}'s source is not the one "
                               "materialx_gltf_spec.py patches (written for 1.39.5)")
        with open(path, "w") as fh:
            fh.write(text.replace(old, new))
    return mx.FileSearchPath(tmp)
