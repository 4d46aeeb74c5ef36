//! The coloured-lobe models (`lobes-*`):
//!
//! - values against `tests/reference/coloured_lobes.py`, an independent
//!   NumPy transcription of the formulas (slope-form `D`, `Lambda` from
//!   `tan theta`, F82 from its definition, conductor Fresnel by complex
//!   Snell, the coat by Fresnel's sin/tan ratios), whose output
//!   `coloured_lobes.json` is committed beside it, to 1e-12 relative, with
//!   the parameter names in the documented order;
//! - hand-derived values at the pole and the two masking forms' order;
//! - analytic derivatives against central finite differences;
//! - reciprocity, non-negativity and finiteness at the box corners and
//!   inside, zero below the horizon, the batch against the single point;
//! - energy: albedo at most 1 for `kd + sum ks <= 1`, for a white F82 lobe,
//!   a conductor lobe and the coat alone, and above 1 just outside.

use std::f64::consts::PI;

use brdf_core::{
    AlbedoFrame, Brdf, DirPairs, Parametric, QuadratureOptions, central_difference_grad,
    directional_albedo, spherical_to_cartesian,
};
use brdf_models::ModelConfig;
use brdf_models::coloured_lobes::{self, VARIANTS};
use nalgebra::Vector3;

fn model(name: &str, channels: usize, lobes: usize) -> Box<dyn Parametric> {
    let config = ModelConfig {
        channels,
        lobes,
        ..ModelConfig::default()
    };
    coloured_lobes::build(name, &config)
        .expect("a coloured-lobe configuration")
        .expect("valid structure")
}

fn with(name: &str, channels: usize, lobes: usize, p: &[f64]) -> Box<dyn Parametric> {
    let mut m = model(name, channels, lobes);
    m.set_params(p).expect("parameters in the box");
    m
}

#[derive(serde::Deserialize)]
struct Case {
    model: String,
    channels: usize,
    lobes: usize,
    names: Vec<String>,
    params: Vec<f64>,
    wi: [f64; 3],
    wo: [f64; 3],
    values: Vec<f64>,
}

#[test]
fn values_match_the_independent_numpy_script() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/reference/coloured_lobes.json"
    ))
    .expect("reference file");
    let cases: Vec<Case> = serde_json::from_str(&text).expect("reference JSON");
    assert_eq!(cases.len(), 864);
    let mut seen = std::collections::BTreeSet::new();
    let mut below = 0;
    for c in &cases {
        let m = with(&c.model, c.channels, c.lobes, &c.params);
        let names: Vec<&str> = m.param_specs().iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, c.names, "{} parameter order", c.model);
        let (l, v) = (Vector3::from(c.wi), Vector3::from(c.wo));
        let mut f = vec![0.0; c.channels];
        m.eval(&l, &v, &mut f);
        for (k, (&a, &b)) in f.iter().zip(&c.values).enumerate() {
            assert!(
                (a - b).abs() <= 1e-12 * b.abs(),
                "{} ch {k} at wi {:?} wo {:?}: {a} vs reference {b}",
                c.model,
                c.wi,
                c.wo
            );
        }
        if c.values.iter().all(|&x| x == 0.0) {
            below += 1;
        }
        seen.insert(c.model.clone());
    }
    // The script has one pair below the horizon per parameter set.
    assert_eq!(below, 96);
    for v in VARIANTS {
        assert!(seen.contains(v.name), "no reference values for {}", v.name);
    }
}

#[test]
fn pole_value_is_the_hand_derived_one_and_masking_forms_differ_off_it() {
    // Pole: D = 1/(pi a^2), G = 1, V.H = 1. kd, ks1, alpha1, coat_ior, coat_alpha.
    let p = [0.25, 0.6, 0.2, 1.5, 0.1];
    let s = |a: f64| 1.0 / (4.0 * PI * a * a);
    let f_coat = 0.04; // ((1.5 - 1)/(1.5 + 1))^2
    let expect = 0.25 / PI + 0.6 * s(0.2) + f_coat * s(0.1);
    for name in ["lobes-coat-mitsuba", "lobes-coat-cycles"] {
        let m = with(name, 1, 1, &p);
        let mut f = [0.0];
        m.eval(&Vector3::z(), &Vector3::z(), &mut f);
        assert!((f[0] - expect).abs() <= 1e-13 * expect, "{name}: {}", f[0]);
    }
    // Off the pole the separable G is the smaller: (1 + a)(1 + b) >= 1 + a + b.
    let (l, v) = (
        spherical_to_cartesian(1.0, 0.0),
        spherical_to_cartesian(1.0, PI),
    );
    let p = [0.0, 1.0, 0.5];
    let (mut a, mut b) = ([0.0], [0.0]);
    with("lobes-mitsuba", 1, 1, &p).eval(&l, &v, &mut a);
    with("lobes-cycles", 1, 1, &p).eval(&l, &v, &mut b);
    assert!(a[0] < b[0] * (1.0 - 1e-3), "{a:?} {b:?}");
}

/// Deterministic points in `[0, 1)` (a 64-bit LCG).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A point strictly inside the box, away from its ends by 5 % of the width.
fn interior(m: &dyn Parametric, rng: &mut Lcg) -> Vec<f64> {
    m.param_specs()
        .iter()
        .map(|s| {
            let w = s.upper - s.lower;
            s.lower + w * (0.05 + 0.9 * rng.next())
        })
        .collect()
}

fn pairs() -> Vec<(Vector3<f64>, Vector3<f64>)> {
    [
        (0.2, 0.0, 0.4, 2.9),
        (0.7, 0.3, 0.6, 3.6),
        (1.2, 1.0, 0.3, 4.0),
        (0.5, 2.0, 1.4, 5.5),
        (1.0, 0.0, 1.0, PI),
    ]
    .iter()
    .map(|&(ti, pi, to, po)| {
        (
            spherical_to_cartesian(ti, pi),
            spherical_to_cartesian(to, po),
        )
    })
    .collect()
}

#[test]
fn derivatives_match_central_differences() {
    let mut rng = Lcg(7);
    for v in VARIANTS {
        for (nc, lobes) in [(1, 1), (3, 2), (3, 3)] {
            let m = model(v.name, nc, lobes);
            let np = m.n_params();
            for _ in 0..3 {
                let p = interior(m.as_ref(), &mut rng);
                for (l, w) in pairs() {
                    let mut f = vec![0.0; nc];
                    let mut g = vec![f64::NAN; nc * np];
                    m.eval_grad_at(&p, &l, &w, &mut f, &mut g);
                    let mut fd = vec![0.0; nc * np];
                    central_difference_grad(m.as_ref(), &p, &l, &w, &mut fd);
                    let mut f2 = vec![0.0; nc];
                    m.eval_at(&p, &l, &w, &mut f2);
                    assert_eq!(f, f2, "{} value with and without gradient", v.name);
                    let scale = f.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                    for i in 0..nc * np {
                        let tol = 1e-6 * (fd[i].abs() + scale) + 1e-12;
                        assert!(
                            (g[i] - fd[i]).abs() <= tol,
                            "{} nc {nc} K {lobes} d/d{} ch {}: {} vs {}",
                            v.name,
                            m.param_specs()[i % np].name,
                            i / np,
                            g[i],
                            fd[i]
                        );
                    }
                }
            }
        }
    }
}

/// Every parameter at an end of its box, by the bits of `mask` (cycled).
fn corner(m: &dyn Parametric, mask: u64) -> Vec<f64> {
    m.param_specs()
        .iter()
        .enumerate()
        .map(|(i, s)| {
            if mask >> (i % 64) & 1 == 1 {
                s.upper
            } else {
                s.lower
            }
        })
        .collect()
}

#[test]
fn reciprocal_non_negative_finite_and_zero_below_the_horizon() {
    let mut rng = Lcg(11);
    for v in VARIANTS {
        for (nc, lobes) in [(1, 1), (3, 3)] {
            let mut m = model(v.name, nc, lobes);
            // MaterialX's compensation depends on the first direction.
            assert_eq!(m.is_reciprocal(), !v.compensated, "{}", v.name);
            let mut points: Vec<Vec<f64>> =
                (0..4).map(|_| interior(m.as_ref(), &mut rng)).collect();
            for mask in [0u64, u64::MAX, 0x5555_5555_5555_5555, 0xAAAA_AAAA_AAAA_AAAA] {
                points.push(corner(m.as_ref(), mask));
            }
            for p in points {
                m.set_params(&p).expect("in the box");
                for (l, w) in pairs() {
                    let (mut a, mut b) = (vec![0.0; nc], vec![0.0; nc]);
                    m.eval(&l, &w, &mut a);
                    m.eval(&w, &l, &mut b);
                    for c in 0..nc {
                        assert!(a[c].is_finite() && a[c] >= 0.0, "{} {p:?}: {a:?}", v.name);
                        assert!(
                            v.compensated || (a[c] - b[c]).abs() <= 1e-13 * a[c].abs(),
                            "{} not reciprocal: {a:?} vs {b:?}",
                            v.name
                        );
                    }
                }
                // Grazing but above: finite; on and below the horizon: 0.
                let g = spherical_to_cartesian(PI / 2.0 - 1e-6, 0.4);
                let mut f = vec![0.0; nc];
                m.eval(&g, &g, &mut f);
                assert!(f.iter().all(|x| x.is_finite() && *x >= 0.0), "{f:?}");
                let under = Vector3::new(0.3, 0.0, -0.2).normalize();
                for (l, w) in [(under, Vector3::z()), (Vector3::z(), under)] {
                    let mut f = vec![1.0; nc];
                    let mut g = vec![1.0; nc * m.n_params()];
                    m.eval_grad_at(&p, &l, &w, &mut f, &mut g);
                    assert!(f.iter().chain(&g).all(|&x| x == 0.0), "{}", v.name);
                }
            }
        }
    }
}

#[test]
fn batch_matches_single_points() {
    let mut rng = Lcg(3);
    let mut dp = DirPairs::with_capacity(8);
    for (l, v) in pairs() {
        dp.push(&l, &v);
    }
    dp.push(&Vector3::new(0.3, 0.0, -0.2).normalize(), &Vector3::z());
    let n = dp.len();
    for v in VARIANTS {
        let m = model(v.name, 3, 2);
        let p = interior(m.as_ref(), &mut rng);
        let mut batch = vec![0.0; 3 * n];
        m.eval_batch_at(&p, &dp, &mut batch);
        let np = m.n_params();
        let (mut bv, mut bj) = (vec![0.0; 3 * n], vec![0.0; 3 * n * np]);
        m.eval_grad_batch_at(&p, &dp, &mut bv, &mut bj);
        for j in 0..n {
            let mut f = [0.0; 3];
            let mut g = vec![0.0; 3 * np];
            m.eval_grad_at(&p, &dp.l(j), &dp.v(j), &mut f, &mut g);
            for c in 0..3 {
                assert_eq!(batch[c * n + j], f[c], "{}", v.name);
                assert_eq!(bv[c * n + j], f[c], "{}", v.name);
                assert_eq!(
                    &bj[(c * n + j) * np..(c * n + j + 1) * np],
                    &g[c * np..(c + 1) * np]
                );
            }
        }
    }
}

#[test]
fn lobe_count_and_channels_are_checked() {
    for v in VARIANTS {
        for lobes in [0, 4] {
            let config = ModelConfig {
                lobes,
                ..ModelConfig::default()
            };
            assert!(coloured_lobes::build(v.name, &config).is_some_and(|r| r.is_err()));
        }
        let config = ModelConfig {
            channels: 0,
            ..ModelConfig::default()
        };
        assert!(coloured_lobes::build(v.name, &config).is_some_and(|r| r.is_err()));
    }
    assert!(coloured_lobes::build("lobes-nothing", &ModelConfig::default()).is_none());
    // Catalogue entries: one per configuration, each building for 1..3 lobes.
    let entries = coloured_lobes::entries();
    assert_eq!(entries.len(), VARIANTS.len());
    for (e, v) in entries.iter().zip(VARIANTS) {
        assert_eq!(e.name, v.name);
        assert!(e.has_lobes);
        for lobes in 1..=3 {
            let c = ModelConfig {
                channels: 3,
                lobes,
                ..ModelConfig::default()
            };
            let m = (e.build)(&c).expect("builds");
            assert_eq!(m.name(), v.name);
            // kd (3) + per lobe 3 or 6 colours and alpha + coat 2.
            let first = if v.first == coloured_lobes::LobeFresnel::None {
                3
            } else {
                6
            };
            let expect = 3 + first + 1 + 4 * (lobes - 1) + if v.coat { 2 } else { 0 };
            assert_eq!(m.n_params(), expect, "{}", v.name);
            let linear = m.param_specs().iter().filter(|s| s.linear).count();
            let ks_lobes = lobes - usize::from(v.first != coloured_lobes::LobeFresnel::None);
            // A compensated lobe's colour enters squared.
            let ks_linear = if v.compensated { 0 } else { 3 * ks_lobes };
            assert_eq!(linear, 3 + ks_linear, "{} linear parameters", v.name);
        }
    }
}

fn worst_albedo(m: &dyn Brdf) -> (f64, f64, f64) {
    let opts = QuadratureOptions {
        rel_tol: 1e-6,
        abs_tol: 1e-9,
        max_intervals: 300,
    };
    let mut w = (f64::NEG_INFINITY, 0.0, 0.0);
    for deg in [0.0f64, 45.0, 75.0, 89.0] {
        let l = spherical_to_cartesian(deg.to_radians(), 0.3);
        let a = directional_albedo(m, &l, AlbedoFrame::Mirror, &opts);
        for c in 0..a.value.len() {
            if a.value[c] + a.error[c] > w.0 + w.1 {
                w = (a.value[c], a.error[c], deg);
            }
        }
    }
    w
}

fn assert_within(name: &str, lobes: usize, p: &[f64]) {
    let m = with(name, 1, lobes, p);
    let (a, e, deg) = worst_albedo(m.as_ref());
    assert!(
        a + e <= 1.0 + 1e-9,
        "{name} {p:?}: albedo {a} + {e} at {deg} deg"
    );
}

#[test]
fn energy_is_conserved_for_colours_summing_to_at_most_one() {
    for name in ["lobes-mitsuba", "lobes-cycles"] {
        assert_within(name, 1, &[0.0, 1.0, 0.05]);
        assert_within(name, 1, &[0.0, 1.0, 1.0]);
        // kd, ks1, alpha1, ks2, alpha2, ks3, alpha3
        assert_within(name, 3, &[0.3, 0.3, 0.01, 0.2, 0.2, 0.2, 1.0]);
    }
    // A white F82 lobe (F0 = 1, tint = 1: F = 1), the darkest F82 lobe, a
    // conductor lobe, each alone.
    assert_within("lobes-f82-cycles", 1, &[0.0, 1.0, 1.0, 0.3]);
    assert_within("lobes-f82-cycles", 1, &[0.0, 0.0, 25.0 / 49.0, 0.3]);
    assert_within("lobes-conductor-mitsuba", 1, &[0.0, 0.01, 10.0, 0.3]);
    assert_within("lobes-conductor-cycles", 1, &[0.0, 0.2, 3.0, 0.05]);
    // The coat alone, at its highest index.
    assert_within("lobes-coat-cycles", 1, &[0.0, 0.0, 0.3, 2.0, 0.1]);
    // Just outside: kd = 0.5 beside a white lobe of colour 0.6 exceeds 1.
    let m = with("lobes-cycles", 1, 1, &[0.5, 0.6, 0.1]);
    let (a, e, deg) = worst_albedo(m.as_ref());
    assert!(a - e > 1.0, "albedo {a} - {e} at {deg} deg should exceed 1");
}

#[test]
fn materialx_compensation_restores_a_white_lobes_energy() {
    // A white lobe (F = 1) times 1 + (1 - E) / E reflects E_true / E_fit of
    // what it receives, E_fit MaterialX's rational fit of the albedo: so
    // the quadrature of the compensated lobe checks the fit's coefficients
    // against an independent albedo. Uncompensated, the same lobe loses
    // energy to single scattering as it widens.
    for alpha in [0.05, 0.3, 0.7] {
        for deg in [0.0f64, 40.0, 70.0] {
            let l = spherical_to_cartesian(deg.to_radians(), 0.0);
            let opts = QuadratureOptions {
                rel_tol: 1e-7,
                abs_tol: 1e-10,
                max_intervals: 400,
            };
            let albedo = |name: &str| {
                let m = with(name, 1, 1, &[0.0, 1.0, alpha]);
                directional_albedo(m.as_ref(), &l, AlbedoFrame::Mirror, &opts).value[0]
            };
            let (plain, comp) = (albedo("lobes-cycles"), albedo("lobes-materialx"));
            let ratio = comp / plain;
            let e_fit = coloured_lobes::compensation::albedo(l.z, alpha).0;
            assert!(
                (ratio - 1.0 / e_fit).abs() < 1e-6 * ratio,
                "alpha {alpha} at {deg} deg: {ratio} vs 1 / {e_fit}"
            );
            assert!(
                (comp - 1.0).abs() < 0.03,
                "alpha {alpha} at {deg} deg: compensated albedo {comp} (uncompensated {plain})"
            );
        }
    }
}

#[test]
fn fresnel_laws_agree_where_they_coincide() {
    let pairs = pairs();
    let eval = |name: &str, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>| {
        let mut f = [0.0];
        with(name, 1, 1, p).eval(l, v, &mut f);
        f[0]
    };
    for (l, v) in &pairs {
        // A conductor of index 1.6 + 0i reflects as the dielectric coat.
        let a = eval("lobes-conductor-cycles", &[0.0, 1.6, 0.0, 0.3], l, v);
        let b = eval("lobes-coat-cycles", &[0.0, 0.0, 0.5, 1.6, 0.3], l, v);
        assert!((a - b).abs() <= 1e-14 * b, "{a} vs {b}");
        // F82 with F0 = 1 and tint 1 reflects everything: the plain white
        // lobe (a tint below 1 darkens the rim even at F0 = 1).
        let a = eval("lobes-f82-cycles", &[0.1, 1.0, 1.0, 0.2], l, v);
        let b = eval("lobes-cycles", &[0.1, 1.0, 0.2], l, v);
        assert!((a - b).abs() <= 1e-14 * b, "{a} vs {b}");
        // Tint 1 is Schlick's law: at F0 = 0.5 above the plain lobe's half.
        let a = eval("lobes-f82-cycles", &[0.0, 0.5, 1.0, 0.2], l, v);
        let b = eval("lobes-cycles", &[0.0, 0.5, 0.2], l, v);
        assert!(a >= b, "{a} vs {b}");
    }
}

#[test]
fn suggested_starts_lie_in_the_box_with_the_widths_apart() {
    for e in coloured_lobes::entries() {
        let starts_fn = e.starts.expect("the coloured-lobe entries suggest starts");
        for lobes in 1..=3 {
            let c = ModelConfig {
                channels: 3,
                lobes,
                ..ModelConfig::default()
            };
            let mut m = (e.build)(&c).expect("builds");
            // The coloured lobes' starts read the model alone, not the data.
            let none = brdf_core::SampleSet::new("none", "none", vec!["grey".into()]);
            let starts = starts_fn(m.as_ref(), &none);
            let conductor = e.name.contains("conductor");
            // Four width sets, reversed too when lobe 1 has a Fresnel law
            // and others follow, for a conductor once per index class.
            let fresnel = conductor || e.name.contains("f82");
            let sets = if fresnel && lobes > 1 { 8 } else { 4 };
            let classes = if conductor { 3 } else { 1 };
            assert_eq!(starts.len(), sets * classes, "{}", e.name);
            for (i, p) in starts.into_iter().enumerate() {
                m.set_params(&p).expect("a start lies in the box");
                let alphas: Vec<f64> = m
                    .param_specs()
                    .iter()
                    .zip(&p)
                    .filter(|(s, _)| s.name.starts_with("alpha"))
                    .map(|(_, &x)| x)
                    .collect();
                assert_eq!(alphas.len(), lobes);
                // Ascending (descending in a reversed set) by a factor of 2
                // at least: lobes start apart.
                let apart = |w: &[f64]| w[1] >= 2.0 * w[0];
                let reversed = i % sets >= 4;
                assert!(
                    alphas.windows(2).all(|w| if reversed {
                        apart(&[w[1], w[0]])
                    } else {
                        apart(w)
                    }),
                    "{alphas:?}"
                );
                // A conductor's index is its class's, everything else at
                // its default.
                let (eta, kappa) = coloured_lobes::CONDUCTOR_INDICES[i / sets];
                for (s, &x) in m.param_specs().iter().zip(&p) {
                    let want = if conductor && s.name.starts_with("eta") {
                        eta
                    } else if conductor && s.name.starts_with("kappa") {
                        kappa
                    } else if s.name.contains("alpha") {
                        continue;
                    } else {
                        s.default
                    };
                    assert_eq!(x, want, "{} {}", e.name, s.name);
                }
            }
        }
    }
    // Another model's layout gets none.
    let lambert = brdf_models::Lambert::with_channels(1).expect("builds");
    assert!(coloured_lobes::suggested_starts(&lambert).is_empty());
}
