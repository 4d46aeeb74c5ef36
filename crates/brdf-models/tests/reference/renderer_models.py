"""Reference values for the renderer models (GGX family, Disney principled as
Mitsuba 3 defines it, glTF 2.0 metallic-roughness with its extensions),
written again from the formulas in plain Python (no code shared with the
Rust crate): the GGX slope-space form of D, Smith Lambda from tan(theta),
Fresnel from Snell's law with complex arithmetic.

Run: python3 renderer_models.py > renderer_models.json
"""

import cmath
import json
import math


def sph(theta, phi):
    return (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))


def half(l, v):
    s = [a + b for a, b in zip(l, v)]
    n = math.sqrt(sum(x * x for x in s))
    return [x / n for x in s]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def ggx_d(h, ax, ay):
    # Walter 2007 eq. 33 in slope form: D = 1 / (pi ax ay cos^4 (1 + tan^2 (cos^2 phi/ax^2 + sin^2 phi/ay^2))^2)
    cos_t = h[2]
    sx, sy = h[0] / cos_t, h[1] / cos_t  # slopes tan(theta) (cos phi, sin phi)
    e = (sx / ax) ** 2 + (sy / ay) ** 2
    return 1.0 / (math.pi * ax * ay * cos_t ** 4 * (1.0 + e) ** 2)


def lam(w, ax, ay):
    theta = math.acos(w[2])
    phi = math.atan2(w[1], w[0])
    a = math.sqrt((ax * math.cos(phi)) ** 2 + (ay * math.sin(phi)) ** 2)
    t = math.tan(theta)
    return (-1.0 + math.sqrt(1.0 + (a * t) ** 2)) / 2.0


def smith(l, v, ax, ay, separable):
    if separable:
        return 1.0 / ((1.0 + lam(l, ax, ay)) * (1.0 + lam(v, ax, ay)))
    return 1.0 / (1.0 + lam(l, ax, ay) + lam(v, ax, ay))


def schlick(f0, c):
    return f0 + (1.0 - f0) * (1.0 - c) ** 5


def fresnel_complex(c, n):
    # Snell: sin t = sin i / n; rs, rp with complex cos t.
    sin_i = math.sqrt(max(0.0, 1.0 - c * c))
    sin_t = sin_i / n
    cos_t = cmath.sqrt(1.0 - sin_t * sin_t)
    if (n * cos_t).real < 0:
        cos_t = -cos_t
    rs = (c - n * cos_t) / (c + n * cos_t)
    rp = (n * c - cos_t) / (n * c + cos_t)
    return 0.5 * (abs(rs) ** 2 + abs(rp) ** 2)


def ggx_spec(l, v, ax, ay, separable):
    h = half(l, v)
    return ggx_d(h, ax, ay) * smith(l, v, ax, ay, separable) / (4.0 * l[2] * v[2]), h


def ggx_family(name, p, l, v):
    aniso = "aniso" in name
    sep = name.endswith("separable")
    kd, ks = p[0], p[1]
    q = p[2:]
    ax, ay = (q[0], q[1]) if aniso else (q[0], q[0])
    rest = q[2:] if aniso else q[1:]
    s, h = ggx_spec(l, v, ax, ay, sep)
    c = dot(v, h)
    if "dielectric" in name:
        f = fresnel_complex(c, complex(rest[0], 0.0))
    elif "conductor" in name:
        f = fresnel_complex(c, complex(rest[0], rest[1]))
    else:
        f = schlick(rest[0], c)
    return [kd / math.pi + ks * s * f]


def ggx_multi(name, p, l, v):
    # kd, then per lobe ks, alpha, f0
    total = p[0] / math.pi
    sep = name.endswith("separable")
    for k in range((len(p) - 1) // 3):
        ks, a, f0 = p[1 + 3 * k: 4 + 3 * k]
        s, h = ggx_spec(l, v, a, a, sep)
        total += ks * s * schlick(f0, dot(v, h))
    return [total]


def sw(c):
    return min(1.0, max(0.0, 1.0 - c)) ** 5


def lum(col):
    if len(col) == 1:
        return col[0]
    return 0.212671 * col[0] + 0.715160 * col[1] + 0.072169 * col[2]


def principled(p, nc, l, v):
    col = p[:nc]
    m, spec, st, rough, aniso, sheen, sheen_tint, cc, ccg = p[nc:]
    h = half(l, v)
    cd = dot(v, h)
    eta = 2.0 / (1.0 - math.sqrt(0.08 * spec)) - 1.0
    r0 = ((eta - 1.0) / (eta + 1.0)) ** 2
    f_diel = fresnel_complex(cd, complex(eta, 0.0))
    aspect = math.sqrt(1.0 - 0.9 * aniso)
    ax = max(0.001, rough ** 2 / aspect)
    ay = max(0.001, rough ** 2 * aspect)
    s, _ = ggx_spec(l, v, ax, ay, True)
    fl, fv = sw(l[2]), sw(v[2])
    rr = 2.0 * rough * cd * cd
    diff = (1 - m) / math.pi * ((1 - 0.5 * fl) * (1 - 0.5 * fv) + rr * (fl + fv + fl * fv * (rr - 1)))
    a = 0.1 * (1 - ccg) + 0.001 * ccg
    d_cc = (a * a - 1) / (math.pi * math.log(a * a) * (1 + (a * a - 1) * h[2] ** 2))
    g_cc = 1.0 / ((1 + lam(l, 0.25, 0.25)) * (1 + lam(v, 0.25, 0.25)))
    coat = cc * 0.25 * schlick(0.04, cd) * d_cc * g_cc
    L = lum(col)
    out = []
    for c in col:
        tint = c / L if L > 0 else 1.0
        f = (1 - m) * (1 - st) * f_diel + m * schlick(c, cd) + (1 - m) * st * schlick(tint * r0, cd)
        c_sheen = 1 + sheen_tint * (tint - 1)
        out.append(f * s + diff * c + sheen * (1 - m) * sw(cd) * c_sheen + coat)
    return out


def gltf(p, nc, l, v, ext):
    col = p[:nc]
    m, rough = p[nc], p[nc + 1]
    if ext:
        ior, spec = p[nc + 2], p[nc + 3]
        sc = p[nc + 4: nc + 4 + nc]
        cc, ccr = p[nc + 4 + nc], p[nc + 5 + nc]
    else:
        ior, spec, sc, cc, ccr = 1.5, 1.0, [1.0] * nc, 0.0, 1.0
    a = rough * rough
    s, h = ggx_spec(l, v, a, a, False)
    vh = abs(dot(v, h))
    f0i = ((ior - 1) / (ior + 1)) ** 2
    fd = []
    for k in range(nc):
        f0 = min(f0i * sc[k], 1.0) * spec
        fd.append(f0 + (spec - f0) * (1 - vh) ** 5)
    fmax = max(fd)
    # N.V of the viewer: the first direction, as renderers evaluate.
    fc = cc * (0.04 + 0.96 * (1 - abs(l[2])) ** 5)
    s_cc, _ = ggx_spec(l, v, ccr * ccr, ccr * ccr, False)
    out = []
    for k in range(nc):
        diel = fd[k] * s + (1 - fmax) * col[k] / math.pi
        metal = s * schlick(col[k], vh)
        mat = (1 - m) * diel + m * metal
        out.append((1 - fc) * mat + fc * s_cc)
    return out


PAIRS = [
    (sph(0.0, 0.0), sph(0.0, 0.0)),
    (sph(0.3, 0.2), sph(0.5, 3.0)),
    (sph(0.7, 1.0), sph(0.6, -2.0)),
    (sph(1.2, 0.4), sph(0.2, 2.5)),
    (sph(1.0, -1.3), sph(1.3, 0.9)),
    (sph(math.pi / 2 - 1e-6, 0.1), sph(0.4, 3.0)),
    (sph(0.9, 0.5), sph(math.pi / 2 - 1e-6, -2.6)),
]

CASES = [
    ("ggx", 1, [0.3, 0.6, 0.15, 0.05]),
    ("ggx", 2, [0.1, 0.4, 0.08, 0.04, 0.3, 0.5, 0.9]),
    ("ggx-separable", 1, [0.2, 0.7, 0.3, 0.5]),
    ("ggx-aniso", 1, [0.2, 0.7, 0.1, 0.4, 0.2]),
    ("ggx-aniso-separable", 1, [0.0, 1.0, 0.5, 0.05, 0.9]),
    ("ggx-dielectric", 1, [0.4, 0.5, 0.25, 1.5]),
    ("ggx-dielectric-separable", 1, [0.4, 0.5, 0.05, 2.4]),
    ("ggx-dielectric-aniso", 1, [0.1, 0.9, 0.3, 0.1, 1.33]),
    ("ggx-dielectric-aniso-separable", 1, [0.1, 0.9, 0.05, 0.6, 1.7]),
    ("ggx-conductor", 1, [0.0, 1.0, 0.2, 0.2, 3.0]),
    ("ggx-conductor-separable", 1, [0.1, 0.8, 0.4, 1.5, 0.0]),
    ("ggx-conductor-aniso", 1, [0.0, 1.0, 0.1, 0.3, 2.8, 4.0]),
    ("ggx-conductor-aniso-separable", 1, [0.05, 0.9, 0.6, 0.2, 0.05, 0.5]),
]

COLOURED = [
    ("principled", 1, [0.8, 0.0, 0.5, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0]),
    ("principled", 3, [0.9, 0.5, 0.1, 0.3, 0.7, 0.6, 0.4, 0.5, 0.8, 0.3, 0.6, 0.9]),
    ("principled", 3, [0.2, 0.6, 0.9, 0.0, 0.2, 0.0, 0.02, 0.0, 0.0, 0.0, 1.0, 1.0]),
    ("principled", 3, [0.5, 0.4, 0.3, 1.0, 0.9, 1.0, 0.3, 1.0, 1.0, 1.0, 0.0, 0.0]),
    ("gltf", 1, [0.5, 0.0, 0.5]),
    ("gltf", 3, [0.9, 0.6, 0.2, 0.4, 0.3]),
    ("gltf", 3, [0.1, 0.2, 0.8, 1.0, 0.8]),
    ("gltf-ext", 3, [0.9, 0.6, 0.2, 0.4, 0.3, 1.8, 0.7, 0.5, 1.2, 2.0, 0.6, 0.2]),
    ("gltf-ext", 3, [0.3, 0.3, 0.3, 0.0, 0.6, 3.0, 1.0, 2.0, 2.0, 2.0, 1.0, 0.05]),
]


def main():
    out = []
    for name, lobes, p in CASES:
        for l, v in PAIRS:
            f = ggx_multi(name, p, l, v) if name in ("ggx", "ggx-separable") else ggx_family(name, p, l, v)
            out.append({"model": name, "channels": 1, "lobes": lobes, "params": p,
                        "wi": list(l), "wo": list(v), "values": f})
    for name, nc, p in COLOURED:
        for l, v in PAIRS:
            if name == "principled":
                f = principled(p, nc, l, v)
            else:
                f = gltf(p, nc, l, v, name == "gltf-ext")
            out.append({"model": name, "channels": nc, "lobes": 1, "params": p,
                        "wi": list(l), "wo": list(v), "values": f})
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
