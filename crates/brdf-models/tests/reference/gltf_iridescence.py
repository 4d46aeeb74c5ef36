"""Reference values for `gltf-iridescence`, the glTF material with
KHR_materials_iridescence, written from the extension's README
("Implementation Notes" and its non-normative GLSL of iridescent_fresnel)
and the glTF 2.0 appendix with NumPy alone (no code shared with the Rust
crate):

- GGX D in slope form, height-correlated Smith masking from Lambda(tan);
- the film: Schlick reflectances at both interfaces (base index from F0 +
  1e-4), phases 0 or pi, R123 clamped to [1e-5, 0.9999], the DC term and
  two orders of the Fourier-domain sum with the Gaussian fits of the
  colour-matching functions, XYZ to Rec. 709, floored at 0; evaluated at
  cos theta_1 = V.H;
- the dielectric with KHR_materials_specular: rgb_mix(diffuse, specular,
  mix(specular fr, film, t)), the metal mix(conductor Schlick, film over
  the base colour, t), mixed by metallic; the clear coat's Schlick at N.V.

Parameter order: base_color (3), metallic, roughness, ior, specular,
specular_color (3), clearcoat, clearcoat_roughness, iridescence,
iridescence_ior, iridescence_thickness.

Run: python3 gltf_iridescence.py > gltf_iridescence.json
"""

import json

import numpy as np

XYZ_TO_REC709 = np.array([
    [3.2404542, -1.5371385, -0.4985314],
    [-0.9692660, 1.8760108, 0.0415560],
    [0.0556434, -0.2040259, 1.0572252],
])


def schlick(f0, c):
    return f0 + (1.0 - f0) * (1.0 - c) ** 5


def eval_sensitivity(opd, shift):
    phase = 2.0 * np.pi * opd * 1.0e-9
    val = np.array([5.4856e-13, 4.4201e-13, 5.2481e-13])
    pos = np.array([1.6810e06, 1.7953e06, 2.2084e06])
    var = np.array([4.3278e09, 9.3046e09, 6.6121e09])
    xyz = val * np.sqrt(2.0 * np.pi * var) * np.cos(pos * phase + shift) * np.exp(-phase**2 * var)
    xyz[0] += 9.7470e-14 * np.sqrt(2.0 * np.pi * 4.5282e09) * np.cos(2.2399e06 * phase + shift[0]) \
        * np.exp(-4.5282e09 * phase**2)
    xyz /= 1.0685e-7
    return XYZ_TO_REC709 @ xyz


def iridescent_fresnel(outside_ior, eta2, base_f0, thickness, cos1):
    r0 = ((eta2 - outside_ior) / (eta2 + outside_ior)) ** 2
    r12 = schlick(r0, cos1)
    t121 = 1.0 - r12
    sin2_sq = (outside_ior / eta2) ** 2 * (1.0 - cos1**2)
    cos2_sq = 1.0 - sin2_sq
    if cos2_sq < 0.0:
        return np.ones(3)
    cos2 = np.sqrt(cos2_sq)
    base_ior = (1.0 + np.sqrt(base_f0 + 1e-4)) / (1.0 - np.sqrt(base_f0 + 1e-4))
    r1 = ((base_ior - eta2) / (base_ior + eta2)) ** 2
    r23 = schlick(r1, cos2)
    phi12 = np.pi if eta2 < outside_ior else 0.0
    phi21 = np.pi - phi12
    phi23 = np.where(base_ior < eta2, np.pi, 0.0)
    phi = phi21 + phi23
    opd = 2.0 * eta2 * thickness * cos2
    r123 = np.clip(r12 * r23, 1e-5, 0.9999)
    rr = np.sqrt(r123)
    rs = t121**2 * r23 / (1.0 - r123)
    i = r12 + rs
    cm = rs - t121
    for m in (1, 2):
        cm = cm * rr
        i = i + cm * 2.0 * eval_sensitivity(m * opd, m * phi)
    return np.maximum(i, 0.0)


def ggx(wi, wo, h, a):
    def tan2(w):
        return (w[0] ** 2 + w[1] ** 2) / w[2] ** 2

    d = 1.0 / (np.pi * a * a * h[2] ** 4 * (1.0 + tan2(h) / (a * a)) ** 2)
    lam = lambda w: (-1.0 + np.sqrt(1.0 + a * a * tan2(w))) / 2.0
    g = 1.0 / (1.0 + lam(wi) + lam(wo))
    return d * g / (4.0 * wi[2] * wo[2])


def evaluate(p, wi, wo, nc):
    base = np.array(p[:nc])
    metallic, rough = p[nc], p[nc + 1]
    ior, specular = p[nc + 2], p[nc + 3]
    sc = np.array(p[nc + 4:2 * nc + 4])
    cc, cc_rough, t, eta2, thick = p[2 * nc + 4:2 * nc + 9]
    if wi[2] <= 0 or wo[2] <= 0:
        return [0.0] * nc
    h = (wi + wo) / np.linalg.norm(wi + wo)
    vdoth = abs(np.dot(wo, h))
    s = ggx(wi, wo, h, rough**2)
    b0 = np.minimum(((1.0 - ior) / (1.0 + ior)) ** 2 * sc, 1.0)
    fr = b0 + (1.0 - b0) * (1.0 - vdoth) ** 5

    def film(f0):
        if nc == 3:
            return iridescent_fresnel(1.0, eta2, f0, thick, vdoth)
        rgb = iridescent_fresnel(1.0, eta2, np.repeat(f0, 3), thick, vdoth)
        return np.array([0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]])

    a = (1.0 - t) * specular * fr + t * film(specular * b0)
    dielectric = (1.0 - a.max()) * base / np.pi + a * s
    metal = s * ((1.0 - t) * (base + (1.0 - base) * (1.0 - vdoth) ** 5) + t * film(base))
    material = (1.0 - metallic) * dielectric + metallic * metal
    # N.V of the viewer: the first direction, as renderers evaluate.
    fc = cc * (0.04 + 0.96 * (1.0 - wi[2]) ** 5)
    out = (1.0 - fc) * material + fc * ggx(wi, wo, h, cc_rough**2)
    return [float(x) for x in out]


def direction(theta_deg, phi_deg):
    t, p = np.radians(theta_deg), np.radians(phi_deg)
    return np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])


PAIRS = [
    ((0.0, 0.0), (0.0, 0.0)),
    ((30.0, 0.0), (30.0, 180.0)),
    ((45.0, 20.0), (40.0, 190.0)),
    ((60.0, 10.0), (20.0, 250.0)),
    ((75.0, 0.0), (75.0, 180.0)),
    ((35.0, 100.0), (65.0, 300.0)),
    ((20.0, 0.0), (100.0, 0.0)),
]


def main():
    rng = np.random.default_rng(20261206)
    cases = []
    for nc in (1, 3):
        for _ in range(6):
            p = list(rng.uniform(0.05, 0.95, nc))  # base colour
            p += [float(rng.uniform(0, 1)), float(rng.uniform(0.1, 0.9))]  # metallic, roughness
            p += [float(rng.uniform(1.2, 2.5)), float(rng.uniform(0.3, 1.0))]  # ior, specular
            p += list(rng.uniform(0.2, 1.8, nc))  # specular colour
            p += [float(rng.uniform(0, 1)), float(rng.uniform(0.05, 0.6))]  # clear coat
            p += [float(rng.uniform(0, 1)), float(rng.uniform(1.05, 2.8)),
                  float(rng.uniform(0, 1500))]  # iridescence
            p = [float(x) for x in p]
            for (ti, pi), (to, po) in PAIRS:
                wi, wo = direction(ti, pi), direction(to, po)
                cases.append({"channels": nc, "params": p, "wi": wi.tolist(), "wo": wo.tolist(),
                              "values": evaluate(p, wi, wo, nc)})
    print(json.dumps(cases, indent=1))


if __name__ == "__main__":
    main()
