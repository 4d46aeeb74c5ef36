"""Reference values for the thin-film models (`film-cycles`,
`film-coat-cycles`), written again from the formula with NumPy alone (no code
shared with the Rust crate):

    f_c = kd_c / pi + w * A_c(mu) * S(alpha) [+ Fdiel(mu; coat_ior) * S(coat_alpha)]

- S(a) = D G2 / (4 N.L N.V): GGX D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2),
  height-correlated Smith G2 = 1 / (1 + Lambda(L) + Lambda(V)) with
  Lambda = (sqrt(1 + a^2 tan^2 theta) - 1) / 2; mu = V.H;
- A_c(mu) = clamp(sum_lambda R(lambda, mu) weight_c(lambda), 0, 1), R the
  unpolarised Airy reflectance of ambient (1) | film (n2, thickness d) |
  base (n3). The interface amplitudes are written with tilted admittances
  (eta = n cos(theta) for s, n / cos(theta) for p; r_ij = (eta_i - eta_j) /
  (eta_i + eta_j)) and cosines from Snell's law in complex arithmetic; each
  R is checked against the characteristic (transfer) matrix of the film;
- weights: CIE 1931 2-degree CMFs (1 nm) alone, i.e. under the
  equal-energy illuminant E (as Blender's Cycles integrates its thin film),
  380..780 nm, plain sums at 1 nm, XYZ to linear sRGB by the IEC 61966-2-1
  matrix; each channel (and Y for one channel) normalised so that R = 1 at
  every wavelength gives exactly 1;
- Fdiel: the exact unpolarised dielectric Fresnel reflectance, by the same
  admittance amplitudes at a single interface.

Parameter order: kd per channel (kd, or kd_r, kd_g, kd_b), w, alpha, film_d
(nm), film_ior, base_ior, then for the coat variant coat_ior, coat_alpha.

`thin_film.json` (written beside this script) holds:
- `cases`: f at direction pairs (pole, mu near 0.2, 1e-6 rad from the
  horizon, below it), with `film_lobe` = w S(alpha), the factor by which an
  error in A reaches f;
- `reflectance`: A alone at mu in {1, 0.9, 0.7, 0.5, 0.3} for several
  (d, n2, n3), with a mirror pair (H = N, V.H = mu) and the lobe S(alpha) there
  so that A = f / S for kd = 0, w = 1;
- `weights`: the 1 nm weight tables, so that `A` works without
  colour-science (Blender's Python imports this module for the Cycles
  check).

Run with numpy and colour-science 0.4.6: python3 thin_film.py
"""

import json
import pathlib

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "thin_film.json"

LAMBDA = np.arange(380.0, 781.0, 1.0)  # nm
XYZ_TO_SRGB = np.array(
    [
        [3.2406, -1.5372, -0.4986],
        [-0.9689, 1.8758, 0.0415],
        [0.0557, -0.2040, 1.0570],
    ]
)
SUFFIX = {1: [""], 3: ["_r", "_g", "_b"]}
MODELS = {"film-cycles": False, "film-coat-cycles": True}


# --- colour weights ---------------------------------------------------------


def weights_from_colour_science():
    """Per-wavelength weights Y, r, g, b, each row summing to 1: the CMFs
    alone (equal-energy illuminant E), mapped to linear sRGB."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import colour

    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    xyz = np.array([cmfs[lam] for lam in LAMBDA])  # tabulated at 1 nm
    rgb = xyz @ XYZ_TO_SRGB.T
    table = {"Y": xyz[:, 1] / xyz[:, 1].sum()}
    for k, c in enumerate("rgb"):
        table[c] = rgb[:, k] / rgb[:, k].sum()
    return table


_WEIGHTS = None


def weights():
    """The weight tables: from colour-science when it is installed, else the
    copy this script stored in thin_film.json."""
    global _WEIGHTS
    if _WEIGHTS is None:
        try:
            _WEIGHTS = weights_from_colour_science()
        except ImportError:
            w = json.loads(OUT.read_text())["weights"]
            assert w.pop("lambda_nm") == LAMBDA.tolist()
            _WEIGHTS = {k: np.array(v) for k, v in w.items()}
    return _WEIGHTS


# --- optics -----------------------------------------------------------------


def cosines(mu, *indices):
    """Complex cosines of the angles in media of the given indices for a ray
    arriving from index 1 at cos(theta) = mu (Snell: n sin = sin_1)."""
    sin1 = np.sqrt(np.maximum(0.0, 1.0 - np.asarray(mu, float) ** 2))
    out = []
    for n in indices:
        c = np.sqrt(1.0 - (sin1 / n) ** 2 + 0j)
        out.append(np.where(c.real < 0, -c, c))
    return out


def admittances(n, c):
    """Tilted admittances (s, p) of a medium of index n at complex cosine c."""
    return n * c, n / c


def amplitude(eta_i, eta_j):
    return (eta_i - eta_j) / (eta_i + eta_j)


def fresnel_dielectric(mu, ior):
    """Unpolarised reflectance of the interface 1 | ior at cos = mu."""
    (c1, c2) = cosines(mu, 1.0, ior)
    s1, p1 = admittances(1.0, c1)
    s2, p2 = admittances(ior, c2)
    return 0.5 * (abs(amplitude(s1, s2)) ** 2 + abs(amplitude(p1, p2)) ** 2)


def airy(mu, d, n2, n3, lam=LAMBDA):
    """Unpolarised reflectance of 1 | n2 (d nm) | n3 at cos = mu, per
    wavelength: |r12 + r23 e^{i phi}|^2 / |1 + r12 r23 e^{i phi}|^2."""
    c1, c2, c3 = cosines(mu, 1.0, n2, n3)
    phi = 2.0 * np.pi * 2.0 * n2 * d * c2 / lam
    e = np.exp(1j * phi)
    total = 0.0
    for pol in (0, 1):
        e1 = admittances(1.0, c1)[pol]
        e2 = admittances(n2, c2)[pol]
        e3 = admittances(n3, c3)[pol]
        r12, r23 = amplitude(e1, e2), amplitude(e2, e3)
        total = total + abs(r12 + r23 * e) ** 2 / abs(1.0 + r12 * r23 * e) ** 2
    return 0.5 * total


def transfer_matrix(mu, d, n2, n3, lam=LAMBDA):
    """The same reflectance by the film's characteristic matrix (a check)."""
    c1, c2, c3 = cosines(mu, 1.0, n2, n3)
    delta = 2.0 * np.pi * n2 * d * c2 / lam
    total = 0.0
    for pol in (0, 1):
        e1 = admittances(1.0, c1)[pol]
        e2 = admittances(n2, c2)[pol]
        e3 = admittances(n3, c3)[pol]
        b = np.cos(delta) + 1j * np.sin(delta) * e3 / e2
        c = 1j * e2 * np.sin(delta) + np.cos(delta) * e3
        total = total + abs((e1 * b - c) / (e1 * b + c)) ** 2
    return 0.5 * total


def A(mu, d, n2, n3, channels=3, clamp=True):
    """Film colour A_c(mu): a list of `channels` values (3: linear sRGB r, g,
    b; 1: Y), each clamped to [0, 1] unless clamp is False; for an array of
    mu, an array of such lists. Illuminant E: the CMFs alone."""
    w = weights()
    rows = np.array([w[c] for c in (("r", "g", "b") if channels == 3 else ("Y",))])
    mu = np.asarray(mu, float)
    out = airy(mu[..., None], d, n2, n3) @ rows.T
    if clamp:
        out = np.clip(out, 0.0, 1.0)
    return out.tolist()


# --- microfacet lobe ----------------------------------------------------------


def tan2(w):
    return (w[0] ** 2 + w[1] ** 2) / w[2] ** 2


def lobe(wi, wo, a):
    """S(a) = D G2 / (4 N.L N.V), GGX, height-correlated Smith."""
    h = (wi + wo) / np.linalg.norm(wi + wo)
    a2 = a * a
    d = a2 / (np.pi * (h[2] ** 2 * (a2 - 1.0) + 1.0) ** 2)
    lam = [(np.sqrt(1.0 + a2 * tan2(w)) - 1.0) / 2.0 for w in (wi, wo)]
    g2 = 1.0 / (1.0 + lam[0] + lam[1])
    return d * g2 / (4.0 * wi[2] * wo[2])


def names(model, nc):
    n = ["kd" + s for s in SUFFIX[nc]]
    n += ["w", "alpha", "film_d", "film_ior", "base_ior"]
    if MODELS[model]:
        n += ["coat_ior", "coat_alpha"]
    return n


def evaluate(model, nc, p, wi, wo):
    """(f per channel, w S(alpha))."""
    v = dict(zip(names(model, nc), p))
    if wi[2] <= 0.0 or wo[2] <= 0.0:
        return [0.0] * nc, 0.0
    h = (wi + wo) / np.linalg.norm(wi + wo)
    mu = float(np.dot(wo, h))
    film = v["w"] * lobe(wi, wo, v["alpha"])
    colour = A(mu, v["film_d"], v["film_ior"], v["base_ior"], nc)
    coat = 0.0
    if MODELS[model]:
        coat = fresnel_dielectric(mu, v["coat_ior"]) * lobe(wi, wo, v["coat_alpha"])
    f = [v["kd" + s] / np.pi + film * a + coat for s, a in zip(SUFFIX[nc], colour)]
    return [float(x) for x in f], float(film)


# --- cases --------------------------------------------------------------------


def direction(theta, phi):
    return np.array([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)])


def deg(theta_deg, phi_deg):
    return direction(np.radians(theta_deg), np.radians(phi_deg))


GRAZING = np.pi / 2.0 - 1e-6
MU02 = np.arccos(0.2)  # mirror pair at this polar angle: V.H = 0.2

PAIRS = [
    (deg(0, 0), deg(0, 0)),  # the pole
    (deg(30, 0), deg(30, 180)),
    (deg(45, 20), deg(40, 190)),
    (deg(60, 10), deg(20, 250)),
    (direction(MU02, 0.3), direction(MU02, 0.3 + np.pi)),  # mu = 0.2 exactly
    (deg(70, 0), deg(85, 180)),  # mu near 0.2 off the mirror direction
    (deg(35, 100), deg(65, 300)),
    (direction(GRAZING, 0.4), deg(40, 200)),  # 1e-6 rad above the horizon
    (direction(GRAZING, 0.0), direction(GRAZING, np.pi)),
    (deg(20, 0), deg(100, 0)),  # below: 0
]

# (film_d, film_ior, base_ior, alpha): every thickness, the index ranges'
# ends, widths from near-mirror to rough.
SETS = [
    (0.0, 1.5, 1.2, 0.2),
    (120.0, 1.3, 2.5, 0.01),
    (250.0, 2.2, 1.2, 0.05),
    (400.0, 1.8, 1.5, 0.6),
    (800.0, 1.4, 2.2, 0.1),
    (1400.0, 2.0, 1.33, 0.35),
]

REFLECTANCE_SETS = [
    (0.0, 1.5, 1.5),
    (0.0, 1.3, 2.5),
    (120.0, 1.3, 1.5),
    (250.0, 1.5, 1.2),
    (250.0, 2.2, 1.5),
    (400.0, 1.8, 2.5),
    (800.0, 1.33, 1.8),
    (1400.0, 2.0, 1.33),
]
REFLECTANCE_MU = [1.0, 0.9, 0.7, 0.5, 0.3]
REFLECTANCE_ALPHA = 0.3


def self_check():
    rng = np.random.default_rng(5)
    for _ in range(50):
        mu = rng.uniform(0.0, 1.0)
        d = rng.uniform(0.0, 1500.0)
        n2, n3 = rng.uniform(1.2, 2.6, 2)
        a, b = airy(mu, d, n2, n3), transfer_matrix(mu, d, n2, n3)
        assert np.max(np.abs(a - b)) < 1e-12, (mu, d, n2, n3)
    # No film: the plain interface; white weights give 1.
    for mu in (1.0, 0.6, 0.1):
        assert np.allclose(airy(mu, 0.0, 1.7, 1.4), fresnel_dielectric(mu, 1.4), atol=1e-15)
    for row in weights().values():
        assert abs(row.sum() - 1.0) < 1e-13
    assert abs(fresnel_dielectric(1.0, 1.5) - 0.04) < 1e-15


def main():
    self_check()
    rng = np.random.default_rng(20261206)
    cases = []
    for model, coat in MODELS.items():
        for nc in (1, 3):
            for d, n2, n3, alpha in SETS:
                p = [float(x) for x in rng.uniform(0.0, 1.0, nc)]
                p += [float(rng.uniform(0.3, 1.0)), alpha, d, n2, n3]
                if coat:
                    p += [float(rng.uniform(1.2, 2.0)), float(rng.uniform(0.02, 0.5))]
                for wi, wo in PAIRS:
                    values, film = evaluate(model, nc, p, wi, wo)
                    cases.append(
                        {
                            "model": model,
                            "channels": nc,
                            "names": names(model, nc),
                            "params": p,
                            "wi": wi.tolist(),
                            "wo": wo.tolist(),
                            "values": values,
                            "film_lobe": film,
                        }
                    )
    reflectance = []
    for d, n2, n3 in REFLECTANCE_SETS:
        for mu in REFLECTANCE_MU:
            theta = float(np.arccos(mu))
            wi, wo = direction(theta, 0.0), direction(theta, np.pi)
            reflectance.append(
                {
                    "film_d": d,
                    "film_ior": n2,
                    "base_ior": n3,
                    "mu": mu,
                    "Y": A(mu, d, n2, n3, 1)[0],
                    "rgb": A(mu, d, n2, n3, 3),
                    "rgb_unclamped": A(mu, d, n2, n3, 3, clamp=False),
                    "alpha": REFLECTANCE_ALPHA,
                    "wi": wi.tolist(),
                    "wo": wo.tolist(),
                    "lobe": float(lobe(wi, wo, REFLECTANCE_ALPHA)),
                }
            )
    w = weights_from_colour_science()
    out = {
        "cases": cases,
        "reflectance": reflectance,
        "weights": {"lambda_nm": LAMBDA.tolist(), **{k: v.tolist() for k, v in w.items()}},
    }
    OUT.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
