"""Independent reference values for brdf-models: every model's formula from
spec/models.md written out again in plain Python (angles and explicit
vectors, no shared code with the Rust implementation), evaluated at fixed
direction pairs including the pole and within 1e-6 rad of the horizon.

Run: python3 models.py > models.json   (standard library only)
"""
import json
import math

PI = math.pi


def vec(theta_deg, phi_deg):
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return [math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def norm(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a]


def half(l, v):
    return norm([a + b for a, b in zip(l, v)])


def schlick(f0, c):
    return f0 + (1 - f0) * (1 - c) ** 5


def fresnel(cos_i, eta):
    ti = math.acos(min(1.0, cos_i))
    if ti == 0.0:
        return ((eta - 1) / (eta + 1)) ** 2
    tt = math.asin(math.sin(ti) / eta)
    if tt == ti:
        return 0.0
    rs = math.sin(ti - tt) / math.sin(ti + tt)
    rp = math.tan(ti - tt) / math.tan(ti + tt)
    return (rs * rs + rp * rp) / 2


def cospow(c, n):
    return max(c, 0.0) ** n if n > 0 else (1.0 if c > 0 else 0.0)


def phong_lobe(l, v, n):
    r = [-l[0], -l[1], l[2]]
    return (n + 2) / (2 * PI) * cospow(dot(r, v), n)


def ward(l, v, kd, ks, ax, ay, duer):
    h = half(l, v)
    delta = math.acos(h[2])
    phih = math.atan2(h[1], h[0])
    t2 = math.tan(delta) ** 2
    e = math.exp(-t2 * (math.cos(phih) ** 2 / ax ** 2 + math.sin(phih) ** 2 / ay ** 2))
    d = l[2] * v[2] if duer else math.sqrt(l[2] * v[2])
    return kd / PI + ks * e / (4 * PI * ax * ay * d)


def lafortune(l, v, kd, lobes):
    f = kd / PI
    for ks, cx, cy, cz, n in lobes:
        c = cx * l[0] * v[0] + cy * l[1] * v[1] + cz * l[2] * v[2]
        f += ks * (n + 2) / (2 * PI * max(abs(cx), abs(cy), abs(cz)) ** n) * cospow(c, n)
    return f


def ashikhmin(l, v, kd, ks, nu, nv, f0, coupled, fresnel_on=True):
    h = half(l, v)
    phih = math.atan2(h[1], h[0]) if (h[0] or h[1]) else math.pi / 4
    e = nu * math.cos(phih) ** 2 + nv * math.sin(phih) ** 2
    vh = dot(v, h)
    spec = math.sqrt((nu + 1) * (nv + 1)) / (8 * PI) * h[2] ** e / (vh * max(l[2], v[2]))
    if fresnel_on:
        spec *= schlick(f0, vh)
    if coupled:
        diff = 28 * kd / (23 * PI) * (1 - f0) * (1 - (1 - l[2] / 2) ** 5) * (1 - (1 - v[2] / 2) ** 5)
    else:
        diff = kd / PI
    return diff + ks * spec


def angles(l, v):
    ti, to = math.acos(l[2]), math.acos(v[2])
    dphi = math.atan2(v[1], v[0]) - math.atan2(l[1], l[0])
    return ti, to, math.cos(dphi)


def oren_nayar(l, v, kd, sigma):
    ti, to, c = angles(l, v)
    a, b = max(ti, to), min(ti, to)
    s2 = sigma ** 2
    A = 1 - 0.5 * s2 / (s2 + 0.33)
    B = 0.45 * s2 / (s2 + 0.09)
    return kd / PI * (A + B * max(0.0, c) * math.sin(a) * math.tan(b))


def oren_nayar_full(l, v, kd, sigma):
    ti, to, c = angles(l, v)
    a, b = max(ti, to), min(ti, to)
    s2 = sigma ** 2
    c1 = 1 - 0.5 * s2 / (s2 + 0.33)
    if c >= 0:
        c2 = 0.45 * s2 / (s2 + 0.09) * math.sin(a)
    else:
        c2 = 0.45 * s2 / (s2 + 0.09) * (math.sin(a) - (2 * b / PI) ** 3)
    c3 = 0.125 * s2 / (s2 + 0.09) * (4 * a * b / PI ** 2) ** 2
    f1 = kd / PI * (c1 + c * c2 * math.tan(b) + (1 - abs(c)) * c3 * math.tan((a + b) / 2))
    f2 = 0.17 * kd ** 2 / PI * s2 / (s2 + 0.13) * (1 - c * (2 * b / PI) ** 2)
    return max(0.0, f1 + f2)


def geom(l, v, h):
    nh, nv, nl, vh = h[2], v[2], l[2], dot(v, h)
    return min(1.0, 2 * nh * nv / vh, 2 * nh * nl / vh)


def torrance_sparrow(l, v, kd, ks, m, f0):
    h = half(l, v)
    delta = math.acos(min(1.0, h[2]))
    d = math.exp(-(delta / m) ** 2) / (PI * m * m)
    return kd / PI + ks * d * geom(l, v, h) * schlick(f0, dot(v, h)) / (l[2] * v[2])


def cook_torrance(l, v, kd, lobes):
    h = half(l, v)
    delta = math.acos(min(1.0, h[2]))
    f = kd / PI
    for ks, m, f0 in lobes:
        d = math.exp(-(math.tan(delta) / m) ** 2) / (m * m * math.cos(delta) ** 4)
        f += ks / PI * d * geom(l, v, h) * schlick(f0, dot(v, h)) / (l[2] * v[2])
    return f


G = 90 - math.degrees(1e-6)  # 1e-6 rad above the horizon
PAIRS = [
    (0, 0, 0, 0),
    (30, 0, 30, 180),
    (45, 10, 60, 200),
    (70, 0, 20, 90),
    (10, 0, 80, 0),
    (60, 30, 60, 30),
    (G, 0, G, 180),
    (G, 30, 10, 100),
    (50, 0, G, 170),
]

MODELS = [
    ("lambert", [0.7], lambda l, v: 0.7 / PI),
    ("phong", [0.2, 0.5, 30.0], lambda l, v: 0.2 / PI + 0.5 * phong_lobe(l, v, 30.0)),
    ("blinn-phong", [0.2, 0.5, 30.0],
     lambda l, v: 0.2 / PI + 0.5 * (32.0) / (2 * PI) * cospow(half(l, v)[2], 30.0)),
    ("ward", [0.2, 0.5, 0.15], lambda l, v: ward(l, v, 0.2, 0.5, 0.15, 0.15, False)),
    ("ward-aniso", [0.2, 0.5, 0.1, 0.3], lambda l, v: ward(l, v, 0.2, 0.5, 0.1, 0.3, False)),
    ("ward-duer", [0.2, 0.5, 0.15], lambda l, v: ward(l, v, 0.2, 0.5, 0.15, 0.15, True)),
    ("ward-duer-aniso", [0.2, 0.5, 0.1, 0.3], lambda l, v: ward(l, v, 0.2, 0.5, 0.1, 0.3, True)),
    ("lafortune", [0.2, 0.5, -0.8, 0.7, 12.0],
     lambda l, v: lafortune(l, v, 0.2, [(0.5, -0.8, -0.8, 0.7, 12.0)])),
    ("lafortune-aniso", [0.2, 0.5, -0.9, -0.6, 0.7, 12.0],
     lambda l, v: lafortune(l, v, 0.2, [(0.5, -0.9, -0.6, 0.7, 12.0)])),
    ("ashikhmin-shirley", [0.2, 0.5, 40.0, 0.3],
     lambda l, v: ashikhmin(l, v, 0.2, 0.5, 40.0, 40.0, 0.3, False)),
    ("ashikhmin-shirley-aniso", [0.2, 0.5, 10.0, 200.0, 0.3],
     lambda l, v: ashikhmin(l, v, 0.2, 0.5, 10.0, 200.0, 0.3, False)),
    ("ashikhmin-shirley-coupled", [0.2, 0.5, 40.0, 0.3],
     lambda l, v: ashikhmin(l, v, 0.2, 0.5, 40.0, 40.0, 0.3, True)),
    ("ashikhmin-shirley-coupled-aniso", [0.2, 0.5, 10.0, 200.0, 0.3],
     lambda l, v: ashikhmin(l, v, 0.2, 0.5, 10.0, 200.0, 0.3, True)),
    ("oren-nayar", [0.6, 0.4], lambda l, v: oren_nayar(l, v, 0.6, 0.4)),
    ("oren-nayar-full", [0.6, 0.4], lambda l, v: oren_nayar_full(l, v, 0.6, 0.4)),
    ("torrance-sparrow", [0.2, 0.5, 0.3, 0.2], lambda l, v: torrance_sparrow(l, v, 0.2, 0.5, 0.3, 0.2)),
    ("cook-torrance", [0.2, 0.5, 0.3, 0.2], lambda l, v: cook_torrance(l, v, 0.2, [(0.5, 0.3, 0.2)])),
    ("phong-fresnel", [0.2, 0.5, 30.0, 1.6],
     lambda l, v: 0.2 / PI + 0.5 * phong_lobe(l, v, 30.0) * (1 - fresnel(l[2], 1.6))),
    ("as-paint", [0.2, 0.5, 40.0],
     lambda l, v: ashikhmin(l, v, 0.2, 0.5, 40.0, 40.0, 0.0, False, fresnel_on=False)),
    ("clear-coat", [0.2, 0.5, 40.0],
     lambda l, v: fresnel(l[2], 1.5) + (1 - fresnel(l[2], 1.5))
     * ashikhmin(l, v, 0.2, 0.5, 40.0, 40.0, 0.0, False, fresnel_on=False)),
]

out = []
for name, params, f in MODELS:
    for ti, pi_, to, po in PAIRS:
        l, v = vec(ti, pi_), vec(to, po)
        out.append({"model": name, "params": params, "wi": l, "wo": v, "value": f(l, v)})
print(json.dumps(out, indent=0))
