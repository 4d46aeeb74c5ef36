"""Reference values for the coloured-lobe models (`lobes-*`), written from
the formulas with NumPy alone (no code shared with the Rust crate):

- GGX D in slope form, 1 / (pi a^2 cos^4(theta_h) (1 + tan^2(theta_h) / a^2)^2);
- Smith Lambda = (-1 + sqrt(1 + a^2 tan^2 theta)) / 2, masking separable
  (1 / ((1 + L_i)(1 + L_o))) or height-correlated (1 / (1 + L_i + L_o));
- F82 tint: Schlick minus a mu (1 - mu)^6, with a fixed by the value at
  mu = 1/7 being tint times Schlick's there;
- conductor: Snell's law in complex arithmetic (complex refraction cosine),
  s and p amplitudes averaged in intensity;
- coat: the dielectric's sin/tan (Fresnel's original) amplitude ratios;
- `-materialx`: each term's colour C times MaterialX 1.39's energy
  compensation 1 + C (1 - E) / E, E the white GGX albedo seen from wi
  (the first direction) by MaterialX's rational fit in (cos, alpha).

Parameter order, per the model's documentation: kd per channel; per lobe k
its colour block(s) (ks; f0 then tint; eta then kappa), each per channel,
then alpha_k; then coat_ior, coat_alpha.

Run: python3 coloured_lobes.py > coloured_lobes.json
"""

import json

import numpy as np

VARIANTS = {
    # name: (separable masking, Fresnel law of lobe 1, coat[, compensated])
    "lobes-mitsuba": (True, "none", False),
    "lobes-cycles": (False, "none", False),
    "lobes-coat-mitsuba": (True, "none", True),
    "lobes-coat-cycles": (False, "none", True),
    "lobes-conductor-mitsuba": (True, "conductor", False),
    "lobes-conductor-cycles": (False, "conductor", False),
    "lobes-conductor-coat-mitsuba": (True, "conductor", True),
    "lobes-conductor-coat-cycles": (False, "conductor", True),
    "lobes-f82-cycles": (False, "f82", False),
    "lobes-f82-coat-cycles": (False, "f82", True),
    "lobes-materialx": (False, "none", False, True),
    "lobes-coat-materialx": (False, "none", True, True),
    "lobes-conductor-materialx": (False, "conductor", False, True),
    "lobes-conductor-coat-materialx": (False, "conductor", True, True),
    "lobes-f82-materialx": (False, "f82", False, True),
    "lobes-f82-coat-materialx": (False, "f82", True, True),
}

# MaterialX's fit of the GGX directional albedo (mx_ggx_dir_albedo_analytic):
# numerator / denominator pairs, rows per monomial.
MX_FIT = np.array([
    [0.1003, 0.9345, 1.0, 1.0],
    [-0.6303, -2.323, -1.765, 0.2281],
    [9.748, 2.229, 8.263, 15.94],
    [-2.038, -3.748, 11.53, -55.83],
    [29.34, 1.424, 28.96, 13.08],
    [-8.245, -0.7684, -7.507, 41.26],
    [-26.44, 1.436, -36.11, 54.9],
    [19.99, 0.2913, 15.86, 300.2],
    [-5.448, 0.6286, 33.37, -285.1],
])


def mx_albedo(x, y):
    mono = np.array([1, x, y, x * y, x * x, y * y, x * x * y, x * y * y, x * x * y * y])
    r = mono @ MX_FIT
    return float(np.clip(r[0] / r[2], 0, 1) + np.clip(r[1] / r[3], 0, 1))


def compensate(colour, wi, a, compensated):
    if not compensated:
        return colour
    e = mx_albedo(wi[2], a)
    return colour * (1.0 + colour * (1.0 - e) / e)

SUFFIX = {1: [""], 3: ["_r", "_g", "_b"]}


def direction(theta_deg, phi_deg):
    t, p = np.radians(theta_deg), np.radians(phi_deg)
    return np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])


def tan_theta(w):
    return np.hypot(w[0], w[1]) / w[2]


def ggx_d(h, a):
    t = tan_theta(h)
    return 1.0 / (np.pi * a * a * h[2] ** 4 * (1.0 + t * t / (a * a)) ** 2)


def smith_lambda(w, a):
    t = tan_theta(w)
    return (-1.0 + np.sqrt(1.0 + a * a * t * t)) / 2.0


def masking(wi, wo, a, separable):
    li, lo = smith_lambda(wi, a), smith_lambda(wo, a)
    if separable:
        return 1.0 / ((1.0 + li) * (1.0 + lo))
    return 1.0 / (1.0 + li + lo)


def lobe(wi, wo, h, a, separable):
    return ggx_d(h, a) * masking(wi, wo, a, separable) / (4.0 * wi[2] * wo[2])


def schlick(f0, mu):
    return f0 + (1.0 - f0) * (1.0 - mu) ** 5


def f82_tint(f0, tint, mu):
    mb = 1.0 / 7.0
    a = schlick(f0, mb) * (1.0 - tint) / (mb * (1.0 - mb) ** 6)
    return schlick(f0, mu) - a * mu * (1.0 - mu) ** 6


def conductor(mu, eta, kappa):
    n = complex(eta, kappa)
    sin_i = np.sqrt(max(0.0, 1.0 - mu * mu))
    cos_t = np.sqrt(complex(1.0 - (sin_i / n) ** 2))
    if (n * cos_t).real < 0:
        cos_t = -cos_t
    rs = (mu - n * cos_t) / (mu + n * cos_t)
    rp = (n * mu - cos_t) / (n * mu + cos_t)
    return 0.5 * (abs(rs) ** 2 + abs(rp) ** 2)


def dielectric(mu, ior):
    ti = np.arccos(min(1.0, mu))
    if ti < 1e-7:
        return ((ior - 1.0) / (ior + 1.0)) ** 2
    tt = np.arcsin(np.sin(ti) / ior)
    rs = np.sin(ti - tt) / np.sin(ti + tt)
    rp = np.tan(ti - tt) / np.tan(ti + tt)
    return 0.5 * (rs * rs + rp * rp)


def layout(law1, coat, nc, lobes):
    """Parameter names and, per name, a sampler of values inside the box."""
    names = []
    kinds = []

    def block(base, kind):
        for s in SUFFIX[nc]:
            names.append(base + s)
            kinds.append(kind)

    block("kd", "unit")
    for k in range(1, lobes + 1):
        law = law1 if k == 1 else "none"
        if law == "none":
            block(f"ks{k}", "unit")
        elif law == "f82":
            block(f"f0{k}", "unit")
            block(f"tint{k}", "tint")
        else:
            block(f"eta{k}", "eta")
            block(f"kappa{k}", "kappa")
        names.append(f"alpha{k}")
        kinds.append("alpha")
    if coat:
        names += ["coat_ior", "coat_alpha"]
        kinds += ["ior", "alpha"]
    return names, kinds


RANGES = {
    "unit": (0.0, 1.0),
    "tint": (25.0 / 49.0, 1.0),
    "eta": (0.05, 3.0),
    "kappa": (0.0, 6.0),
    "alpha": (0.03, 0.8),
    "ior": (1.2, 2.0),
}


def evaluate(name, nc, lobes, p, wi, wo):
    separable, law1, coat, *rest = VARIANTS[name]
    comp = bool(rest and rest[0])
    names, _ = layout(law1, coat, nc, lobes)
    val = dict(zip(names, p))
    if wi[2] <= 0.0 or wo[2] <= 0.0:
        return [0.0] * nc
    h = (wi + wo) / np.linalg.norm(wi + wo)
    mu = float(np.dot(wo, h))
    out = []
    for s in SUFFIX[nc]:
        f = val["kd" + s] / np.pi
        for k in range(1, lobes + 1):
            law = law1 if k == 1 else "none"
            if law == "none":
                colour = val[f"ks{k}{s}"]
            elif law == "f82":
                colour = f82_tint(val[f"f0{k}{s}"], val[f"tint{k}{s}"], mu)
            else:
                colour = conductor(mu, val[f"eta{k}{s}"], val[f"kappa{k}{s}"])
            a = val[f"alpha{k}"]
            f += compensate(colour, wi, a, comp) * lobe(wi, wo, h, a, separable)
        if coat:
            a = val["coat_alpha"]
            colour = compensate(dielectric(mu, val["coat_ior"]), wi, a, comp)
            f += colour * lobe(wi, wo, h, a, separable)
        out.append(float(f))
    return out


PAIRS = [
    ((0.0, 0.0), (0.0, 0.0)),
    ((30.0, 0.0), (30.0, 180.0)),
    ((45.0, 20.0), (40.0, 190.0)),
    ((60.0, 10.0), (20.0, 250.0)),
    ((75.0, 0.0), (75.0, 180.0)),
    ((80.0, 45.0), (10.0, 60.0)),
    ((35.0, 100.0), (65.0, 300.0)),
    ((50.0, 0.0), (50.0, 0.0)),
    ((20.0, 0.0), (100.0, 0.0)),
]


def main():
    rng = np.random.default_rng(20261205)
    cases = []
    for name in VARIANTS:
        separable, law1, coat, *_ = VARIANTS[name]
        for nc, lobes in [(1, 1), (3, 2), (3, 3)]:
            names, kinds = layout(law1, coat, nc, lobes)
            for _ in range(2):
                p = [float(rng.uniform(*RANGES[k])) for k in kinds]
                for (ti, pi), (to, po) in PAIRS:
                    wi, wo = direction(ti, pi), direction(to, po)
                    cases.append(
                        {
                            "model": name,
                            "channels": nc,
                            "lobes": lobes,
                            "names": names,
                            "params": p,
                            "wi": wi.tolist(),
                            "wo": wo.tolist(),
                            "values": evaluate(name, nc, lobes, p, wi, wo),
                        }
                    )
    print(json.dumps(cases, indent=1))


if __name__ == "__main__":
    main()
