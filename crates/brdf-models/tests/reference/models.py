"""Independent reference values for brdf-models: every model's formula from
its paper written out again in plain Python (angles and explicit
vectors, no shared code with the Rust implementation), evaluated at fixed
direction pairs including the pole and within 1e-6 rad of the horizon.

Beyond the one-channel cases it covers: Koenderink's Zernike basis of
orders 2, 4 and 8 at pairs with phi_i != 0 (enumerated from the formula of
Koenderink et al. 1996, radial polynomials by the factorial sum); Kurt's polynomial
(features W1 = ux vx + uy vy, W2 = uz vz and X1..X3, PCA over a fixed
training set with numpy's eigh, scores, design rows and values at new pairs,
degrees 1, 3 and 7); two-lobe Lafortune and Cook-Torrance; three-channel
models; F0 = 0.999; pairs on and below the horizon (value 0).

Run: python3 models.py > models.json   (needs numpy for the PCA only)
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

# ---------------------------------------------------------------------------
# Per-channel cases: every model value is a list, one entry per channel.
# kd and ks are per channel; all other parameters are shared (models.md).

PAIRS_EXTRA = [(35, 120, 55, 250), (80, 300, 40, 60), (20, 200, 75, 190)]
BELOW = [
    ([0.6, 0.0, -0.8], [0.0, 0.6, 0.8]),
    ([0.0, 0.6, 0.8], [0.8, 0.0, -0.6]),
    ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
    ([0.0, 0.0, 1.0], [0.0, -1.0, 0.0]),
]


def split(params, nc):
    return params[:nc], params[nc:]


def per_channel(kd, f_of_kd_ks, ks=None):
    return [f_of_kd_ks(kd[c], None if ks is None else ks[c]) for c in range(len(kd))]


def lobes_model(name, nc, nlobes, per_lobe, make):
    """Parameters kd[nc], then per lobe ks[nc] and `per_lobe` shape values."""
    def f(params, l, v):
        kd = params[:nc]
        lobes = []
        for k in range(nlobes):
            b = nc + k * (nc + per_lobe)
            lobes.append((params[b:b + nc], params[b + nc:b + nc + per_lobe]))
        return [make(l, v, kd[c], [(ks[c], q) for ks, q in lobes]) for c in range(nc)]
    return f


def laf(l, v, kd, lobes):
    out = []
    for ks, q in lobes:
        if len(q) == 3:
            cxy, cz, n = q
            out.append((ks, cxy, cxy, cz, n))
        else:
            cx, cy, cz, n = q
            out.append((ks, cx, cy, cz, n))
    return lafortune(l, v, kd, out)


def ct(l, v, kd, lobes):
    return cook_torrance(l, v, kd, [(ks, q[0], q[1]) for ks, q in lobes])


def diffuse_lobe(nc, shape):
    """kd[nc], ks[nc], q: f_c = kd_c/pi + ks_c S(q)."""
    def f(params, l, v):
        kd, ks, q = params[:nc], params[nc:2 * nc], params[2 * nc:]
        return [shape(l, v, kd[c], ks[c], q) for c in range(nc)]
    return f


def kd_only(nc, g):
    def f(params, l, v):
        return [g(l, v, params[c], params[nc:]) for c in range(nc)]
    return f


RGB = [0.1, 0.3, 0.6]
KS3 = [0.5, 0.4, 0.2]
CASES = [
    # (name, channels, lobes, params, function)
    ("lafortune", 1, 2, [0.2, 0.4, -0.9, 0.8, 20.0, 0.3, 0.6, 0.9, 3.0], lobes_model("lafortune", 1, 2, 3, laf)),
    ("lafortune-aniso", 1, 2, [0.1, 0.4, -0.9, -0.5, 0.8, 15.0, 0.3, -0.95, -0.9, 0.4, 4.0],
     lobes_model("lafortune-aniso", 1, 2, 4, laf)),
    ("lafortune", 3, 2, RGB + KS3 + [-0.9, 0.8, 20.0] + [0.2, 0.1, 0.3] + [0.6, 0.9, 3.0],
     lobes_model("lafortune", 3, 2, 3, laf)),
    ("cook-torrance", 1, 2, [0.2, 0.3, 0.1, 0.9, 0.1, 0.5, 0.05], lobes_model("cook-torrance", 1, 2, 2, ct)),
    ("cook-torrance", 3, 2, RGB + KS3 + [0.15, 0.999] + [0.05, 0.1, 0.08] + [0.6, 0.3],
     lobes_model("cook-torrance", 3, 2, 2, ct)),
    ("cook-torrance", 1, 1, [0.0, 0.4, 0.25, 0.999], lobes_model("cook-torrance", 1, 1, 2, ct)),
    ("lambert", 3, 1, RGB, kd_only(3, lambda l, v, kd, q: kd / PI)),
    ("phong", 3, 1, RGB + KS3 + [45.0], diffuse_lobe(3, lambda l, v, kd, ks, q: kd / PI + ks * phong_lobe(l, v, q[0]))),
    ("ward-aniso", 3, 1, RGB + KS3 + [0.12, 0.35],
     diffuse_lobe(3, lambda l, v, kd, ks, q: ward(l, v, kd, ks, q[0], q[1], False))),
    ("ward-duer", 3, 1, RGB + KS3 + [0.2], diffuse_lobe(3, lambda l, v, kd, ks, q: ward(l, v, kd, ks, q[0], q[0], True))),
    ("ashikhmin-shirley", 3, 1, RGB + KS3 + [60.0, 0.999],
     diffuse_lobe(3, lambda l, v, kd, ks, q: ashikhmin(l, v, kd, ks, q[0], q[0], q[1], False))),
    ("ashikhmin-shirley-coupled", 1, 1, [0.6, 0.3, 25.0, 0.999],
     diffuse_lobe(1, lambda l, v, kd, ks, q: ashikhmin(l, v, kd, ks, q[0], q[0], q[1], True))),
    ("ashikhmin-shirley-coupled-aniso", 3, 1, RGB + KS3 + [5.0, 120.0, 0.999],
     diffuse_lobe(3, lambda l, v, kd, ks, q: ashikhmin(l, v, kd, ks, q[0], q[1], q[2], True))),
    ("torrance-sparrow", 3, 1, RGB + KS3 + [0.2, 0.999],
     diffuse_lobe(3, lambda l, v, kd, ks, q: torrance_sparrow(l, v, kd, ks, q[0], q[1]))),
    ("oren-nayar", 3, 1, RGB + [0.7], kd_only(3, lambda l, v, kd, q: oren_nayar(l, v, kd, q[0]))),
    ("oren-nayar-full", 3, 1, [0.2, 0.5, 0.9, 0.8], kd_only(3, lambda l, v, kd, q: oren_nayar_full(l, v, kd, q[0]))),
    ("phong-fresnel", 3, 1, RGB + KS3 + [12.0, 2.2],
     diffuse_lobe(3, lambda l, v, kd, ks, q: kd / PI + ks * phong_lobe(l, v, q[0]) * (1 - fresnel(l[2], q[1])))),
    ("as-paint", 3, 1, RGB + KS3 + [80.0],
     diffuse_lobe(3, lambda l, v, kd, ks, q: ashikhmin(l, v, kd, ks, q[0], q[0], 0.0, False, fresnel_on=False))),
    ("clear-coat", 3, 1, RGB + KS3 + [80.0],
     diffuse_lobe(3, lambda l, v, kd, ks, q: fresnel(l[2], 1.5) + (1 - fresnel(l[2], 1.5))
                  * ashikhmin(l, v, kd, ks, q[0], q[0], 0.0, False, fresnel_on=False))),
]


def case(name, nc, nlobes, params, l, v, value):
    return {"model": name, "channels": nc, "lobes": nlobes, "params": params, "wi": l, "wo": v,
            "value": value}


cases = []
for name, params, f in MODELS:
    for ti, pi_, to, po in PAIRS:
        l, v = vec(ti, pi_), vec(to, po)
        cases.append(case(name, 1, 1, params, l, v, [f(l, v)]))
    # Below and on the horizon every model returns 0.
    for l, v in BELOW:
        cases.append(case(name, 1, 1, params, l, v, [0.0]))
for name, nc, nlobes, params, f in CASES:
    for ti, pi_, to, po in PAIRS + PAIRS_EXTRA:
        l, v = vec(ti, pi_), vec(to, po)
        cases.append(case(name, nc, nlobes, params, l, v, f(params, l, v)))
    for l, v in BELOW:
        cases.append(case(name, nc, nlobes, params, l, v, [0.0] * nc))

# ---------------------------------------------------------------------------
# Koenderink: the basis in the documented order (m, then n, then n'), each
# R_n^m from the factorial sum, at pairs with phi_i != 0.


def zernike(n, m, rho):
    f = math.factorial
    return sum((-1) ** k * f(n - k) / (f(k) * f((n + m) // 2 - k) * f((n - m) // 2 - k)) * rho ** (n - 2 * k)
               for k in range((n - m) // 2 + 1))


def koenderink_basis(order, l, v):
    ti, to = math.acos(l[2]), math.acos(v[2])
    ri, ro = math.sqrt(2) * math.sin(ti / 2), math.sqrt(2) * math.sin(to / 2)
    pi_, po = math.atan2(l[1], l[0]), math.atan2(v[1], v[0])
    out = []
    for m in range(order + 1):
        for n in range(m, order + 1, 2):
            for n2 in range(n, order + 1, 2):
                r = zernike(n, m, ri) * zernike(n2, m, ro)
                if n != n2:
                    r += zernike(n2, m, ri) * zernike(n, m, ro)
                out.append(r * math.cos(m * (pi_ - po)))
    return out


K_PAIRS = [(30, 40, 50, 100), (60, 170, 20, 300), (75, 250, 65, 10), (15, 90, 85, 200),
           (45, 315, 45, 135), (5, 100, 70, 350)]
koenderink = []
for order in (2, 4, 8):
    for j, (ti, pi_, to, po) in enumerate(K_PAIRS):
        l, v = vec(ti, pi_), vec(to, po)
        b = koenderink_basis(order, l, v)
        # Coefficients: a constant that keeps the sum positive plus a
        # deterministic pattern over the higher functions.
        coef = [0.5] + [0.05 * math.sin(1.3 * k + j) for k in range(1, len(b))]
        koenderink.append({"order": order, "wi": l, "wo": v, "basis": b, "coef": coef,
                           "value": max(0.0, sum(c * x for c, x in zip(coef, b)))})

# ---------------------------------------------------------------------------
# Kurt's polynomial: features from the formulas, PCA (centre, covariance,
# eigh, decreasing eigenvalue, sign: largest-magnitude component positive).
import numpy as np  # noqa: E402


def features(aniso, l, v):
    if aniso:
        return [l[0] * v[0], l[1] * v[1], l[2] * v[2]]
    return [l[0] * v[0] + l[1] * v[1], l[2] * v[2]]


TRAIN = []
for i in range(40):
    # A fixed, irregular set of pairs over the hemisphere.
    ti, pi_ = 5 + (37 * i) % 80, (53 * i + 11) % 360
    to, po = 3 + (61 * i + 7) % 84, (97 * i + 200) % 360
    TRAIN.append((vec(ti, pi_), vec(to, po)))
TEST = [vec_pair for vec_pair in [(vec(25, 35), vec(50, 190)), (vec(70, 300), vec(10, 80)),
                                   (vec(40, 0), vec(40, 180)), (vec(85, 120), vec(60, 250)),
                                   (vec(0, 0), vec(30, 45)), (vec(55, 210), vec(75, 215))]]


def pca(aniso):
    w = np.array([features(aniso, l, v) for l, v in TRAIN])
    mean = w.mean(axis=0)
    cov = np.cov((w - mean).T, ddof=1)
    vals, vecs = np.linalg.eigh(cov)
    order = np.argsort(-vals)
    axes = []
    for i in order:
        e = vecs[:, i]
        if e[np.argmax(np.abs(e))] < 0:
            e = -e
        axes.append(e)
    return mean, np.array(axes), vals[order]


polynomial = {"train": [{"wi": l, "wo": v} for l, v in TRAIN], "cases": []}
for aniso in (False, True):
    mean, axes, variances = pca(aniso)
    d = len(mean)
    name = "polynomial-aniso" if aniso else "polynomial"
    polynomial[name] = {"mean": mean.tolist(), "axes": axes.flatten().tolist(),
                        "variances": variances.tolist()}
    for degree in (1, 3, 7):
        for nc in (1, 3):
            per = d * degree + 1
            coef = [0.3 + 0.1 * c if k == 0 else 0.2 * math.cos(0.7 * k + c) / k
                    for c in range(nc) for k in range(per)]
            for l, v in TEST:
                w = features(aniso, l, v)
                z = axes @ (np.array(w) - mean)
                row = [1.0]
                for k in range(1, degree + 1):
                    row += [float(zi ** k) for zi in z]
                value = [max(0.0, sum(a * b for a, b in zip(row, coef[c * per:(c + 1) * per])))
                         for c in range(nc)]
                polynomial["cases"].append({"model": name, "degree": degree, "channels": nc,
                                            "params": coef, "wi": l, "wo": v, "features": w,
                                            "scores": z.tolist(), "row": row, "value": value})

# One record per line, so a regenerated file diffs readably.
lines = ['{"cases": [', ",\n".join(json.dumps(c) for c in cases), '], "koenderink": [',
         ",\n".join(json.dumps(c) for c in koenderink), '], "polynomial": {',
         ",\n".join(f"{json.dumps(k)}: {json.dumps(v)}" for k, v in polynomial.items()), "}}"]
print("\n".join(lines))
