//! The thin-film models (`film-cycles`, `film-coat-cycles`) against
//! independently computed values: `tests/reference/thin_film.py` writes the
//! formula again in NumPy (tilted-admittance Fresnel amplitudes with complex
//! Snell cosines, each Airy reflectance checked against the film's
//! characteristic matrix; CIE 1931 CMFs from colour-science under the
//! equal-energy illuminant E, as Cycles integrates its film, plain sums at
//! 1 nm; no shared code) and evaluates it at fixed pairs, among them
//! the pole, `mu = 0.2`, pairs within 1e-6 rad of the horizon and a pair
//! below it; `thin_film.json` holds its output: one and three channels,
//! thicknesses 0, 120, 250, 400, 800 and 1400 nm, film indices 1.3-2.2, base
//! indices 1.2-2.5, widths 0.01-0.6, and the film colour `A_c(mu)` alone at
//! `mu` in {1, 0.9, 0.7, 0.5, 0.3} for eight films.
//!
//! The tolerance is on `A`, carried to `f` by the factor that multiplies it
//! there (`w S(alpha)`, stored with each case): the script integrates over
//! wavelength by plain sums at 1 nm, the model by its own quadrature, so the
//! film colours differ by a quadrature error, while the rest of the formula
//! (Lambert, GGX, masking, the coat's Fresnel) is the same arithmetic in
//! another order (relative [`REL`]). A relative bound on `f` alone would be
//! loose where the specular lobe dominates and fail where `A` is small
//! (anti-reflecting films, `A` near 0.003) and the quadrature's absolute
//! error a large part of it. Measured: `|A - A_ref|` at most 1.5e-5 with a
//! film (bound [`A_TOL`]) and 1.2e-6 without one, where no quadrature
//! enters but the model's colour is still not the bare Fresnel to rounding
//! (bound [`PLAIN_A_TOL`]); both are printed by the tests.

use brdf_core::Parametric;
use brdf_models::{ModelConfig, build};
use nalgebra::Vector3;

/// Absolute bound on the film colour `A_c`, either quadrature against the
/// other (1.5e-5 measured, at 1400 nm).
const A_TOL: f64 = 1e-4;
/// Absolute bound on `A_c` without a film, the base's plain Fresnel
/// (1.2e-6 measured, near grazing).
const PLAIN_A_TOL: f64 = 5e-6;
/// Relative bound on everything but the film colour's quadrature.
const REL: f64 = 1e-9;

#[derive(serde::Deserialize)]
struct Case {
    model: String,
    channels: usize,
    names: Vec<String>,
    params: Vec<f64>,
    wi: [f64; 3],
    wo: [f64; 3],
    values: Vec<f64>,
    /// `w S(alpha)`: the factor by which an error in `A` reaches `f`.
    film_lobe: f64,
}

#[derive(serde::Deserialize)]
struct Reflectance {
    film_d: f64,
    film_ior: f64,
    base_ior: f64,
    mu: f64,
    #[serde(rename = "Y")]
    y: f64,
    rgb: [f64; 3],
    alpha: f64,
    wi: [f64; 3],
    wo: [f64; 3],
    /// `S(alpha)` at the mirror pair `wi`, `wo`.
    lobe: f64,
}

#[derive(serde::Deserialize)]
struct Reference {
    cases: Vec<Case>,
    reflectance: Vec<Reflectance>,
}

fn reference() -> Reference {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/reference/thin_film.json"
    ))
    .expect("reference file");
    serde_json::from_str(&text).expect("reference JSON")
}

fn model(name: &str, channels: usize) -> Box<dyn Parametric> {
    let config = ModelConfig {
        channels,
        lobes: 1,
        order: 8,
        degree: 7,
    };
    build(name, &config).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn values_match_the_independent_numpy_script() {
    let r = reference();
    assert_eq!(r.cases.len(), 240);
    let mut seen = std::collections::BTreeSet::new();
    let (mut below, mut worst_a, mut worst_plain) = (0, 0.0f64, 0.0f64);
    for c in &r.cases {
        let m = model(&c.model, c.channels);
        let names: Vec<&str> = m.param_specs().iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, c.names, "{} parameter order", c.model);
        let (l, v) = (Vector3::from(c.wi), Vector3::from(c.wo));
        let mut f = vec![f64::NAN; c.channels];
        m.eval_at(&c.params, &l, &v, &mut f);
        for (k, (&got, &want)) in f.iter().zip(&c.values).enumerate() {
            // Without a film the colour is the base's Fresnel: no
            // quadrature error (the weights sum to 1 either way).
            let plain = c.params[c.channels + 2] == 0.0;
            let a_tol = if plain { PLAIN_A_TOL } else { A_TOL };
            let tol = a_tol * c.film_lobe + REL * want.abs();
            assert!(
                got.is_finite() && (got - want).abs() <= tol,
                "{} ({} channels) ch {k} at wi {:?} wo {:?}, params {:?}: {got} vs reference {want} (tolerance {tol})",
                c.model,
                c.channels,
                c.wi,
                c.wo,
                c.params
            );
            if c.film_lobe > 0.0 {
                let implied = (got - want).abs() / c.film_lobe;
                if plain {
                    worst_plain = worst_plain.max(implied);
                } else {
                    worst_a = worst_a.max(implied);
                }
            }
        }
        if c.wi[2] <= 0.0 || c.wo[2] <= 0.0 {
            assert!(
                f.iter().all(|&x| x == 0.0),
                "{}: {f:?} below the horizon",
                c.model
            );
            below += 1;
        }
        seen.insert((c.model.clone(), c.channels));
    }
    eprintln!(
        "largest |A - A_ref| implied by f: {worst_a:.2e} with a film, {worst_plain:.2e} without"
    );
    // One pair below the horizon per parameter set: 2 models x 2 channel
    // counts x 6 sets.
    assert_eq!(below, 24);
    for name in ["film-cycles", "film-coat-cycles"] {
        for nc in [1, 3] {
            assert!(
                seen.contains(&(name.to_string(), nc)),
                "no values for {name} ({nc})"
            );
        }
    }
}

#[test]
fn film_colour_alone_matches_the_independent_script() {
    let r = reference();
    assert_eq!(r.reflectance.len(), 40);
    let mut worst = (0.0f64, String::new());
    for c in &r.reflectance {
        let (l, v) = (Vector3::from(c.wi), Vector3::from(c.wo));
        // kd = 0, w = 1: f = A S(alpha) at the mirror pair.
        for (nc, want) in [(1, vec![c.y]), (3, c.rgb.to_vec())] {
            let m = model("film-cycles", nc);
            let mut p = vec![0.0; nc];
            p.extend([1.0, c.alpha, c.film_d, c.film_ior, c.base_ior]);
            let mut f = vec![f64::NAN; nc];
            m.eval_at(&p, &l, &v, &mut f);
            for (k, (&got, &want)) in f.iter().zip(&want).enumerate() {
                let a = got / c.lobe;
                let dev = (a - want).abs();
                let bound = if c.film_d == 0.0 { PLAIN_A_TOL } else { A_TOL };
                assert!(
                    dev <= bound,
                    "d {} nm, n2 {}, n3 {}, mu {}, {nc} channels, ch {k}: A {a} vs reference {want}",
                    c.film_d,
                    c.film_ior,
                    c.base_ior,
                    c.mu
                );
                if dev > worst.0 {
                    worst = (
                        dev,
                        format!(
                            "d {} n2 {} n3 {} mu {} nc {nc} ch {k}",
                            c.film_d, c.film_ior, c.base_ior, c.mu
                        ),
                    );
                }
            }
        }
        // Without a film the colour is the base's Fresnel in every channel,
        // which no quadrature changes.
        if c.film_d == 0.0 {
            for x in c.rgb {
                assert!((x - c.y).abs() <= 1e-12, "{:?} vs {}", c.rgb, c.y);
            }
        }
    }
    eprintln!("largest |A - A_ref|: {:.2e} ({})", worst.0, worst.1);
}
