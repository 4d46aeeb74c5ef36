//! Mitsuba 3 round trip: `tests/reference/mitsuba_check.py` loaded every
//! exported `<bsdf>` of `tests/export/cases.rs` in Mitsuba 3 (scalar_rgb) and
//! evaluated it at 300 direction pairs spread over the hemisphere up to
//! 85 deg (components rounded to single precision, so both sides evaluate
//! at the same directions) and at the normal; `mitsuba_values.json` holds
//! Mitsuba's values divided by `cos theta_o`. The exporter must still write
//! the XML Mitsuba evaluated, and the model must equal Mitsuba's BSDF to
//! 1e-4 relative at every pair.

use crate::cases;

use brdf_core::Parametric;

#[derive(serde::Deserialize)]
struct Fixture {
    mitsuba: String,
    cases: Vec<Checked>,
}

#[derive(serde::Deserialize)]
struct Checked {
    model: String,
    channels: usize,
    lobes: usize,
    params: Vec<f64>,
    xml: String,
    pairs: Vec<([f64; 3], [f64; 3])>,
    values: Vec<[f64; 3]>,
    peak: [f64; 3],
}

fn fixture() -> Fixture {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/reference/mitsuba_values.json"
    ))
    .expect("fixture present");
    serde_json::from_str(&text).expect("fixture parses")
}

/// Our value at `(wi, wo)` (Mitsuba's `wi` is our `V`, its `wo` our `L`).
fn ours(m: &dyn Parametric, wi: &[f64; 3], wo: &[f64; 3]) -> Vec<f64> {
    let (l, v) = (nalgebra::Vector3::from(*wo), nalgebra::Vector3::from(*wi));
    let mut f = vec![0.0; m.channels()];
    m.eval(&l, &v, &mut f);
    (0..3).map(|k| f[k.min(f.len() - 1)]).collect()
}

fn rel(ours: f64, theirs: f64) -> f64 {
    (ours - theirs).abs() / ours.abs().max(1e-3)
}

#[test]
fn exports_equal_mitsubas_own_evaluation() {
    let fx = fixture();
    assert_eq!(fx.cases.len(), cases::cases().len());
    eprintln!("reference: Mitsuba {}", fx.mitsuba);
    for c in &fx.cases {
        let m = cases::build(&c.model, c.channels, c.lobes, &c.params);
        let xml = brdf_export::export(m.as_ref(), brdf_export::Target::Mitsuba).unwrap();
        assert_eq!(
            xml, c.xml,
            "{}: exporter output changed; rerun the script",
            c.model
        );
        assert_eq!(c.pairs.len(), 300);
        let mut worst = 0.0f64;
        for ((wi, wo), mv) in c.pairs.iter().zip(&c.values) {
            let f = ours(m.as_ref(), wi, wo);
            worst = (0..3).map(|k| rel(f[k], mv[k])).fold(worst, f64::max);
        }
        eprintln!(
            "{} ({} ch): worst relative deviation {worst:.3e}",
            c.model, c.channels
        );
        assert!(
            worst <= 1e-4,
            "{}: worst relative deviation from Mitsuba {worst}",
            c.model
        );
    }
}

/// The pairs cover the hemisphere: both polar angles reach past 70 deg and
/// every azimuth quadrant holds pairs (an earlier generator kept every
/// pair within 34 deg of the normal).
#[test]
fn pairs_cover_the_hemisphere() {
    let fx = fixture();
    let pairs = &fx.cases[0].pairs;
    let max_theta = |side: usize| {
        pairs
            .iter()
            .map(|p| if side == 0 { p.0 } else { p.1 }[2].acos().to_degrees())
            .fold(0.0, f64::max)
    };
    assert!(max_theta(0) > 70.0 && max_theta(1) > 70.0);
    for q in 0..4 {
        let n = pairs
            .iter()
            .filter(|(wi, _)| {
                let phi = wi[1].atan2(wi[0]).rem_euclid(std::f64::consts::TAU);
                (phi / std::f64::consts::FRAC_PI_2) as usize == q
            })
            .count();
        assert!(n > 40, "quadrant {q}: {n} pairs");
    }
}

/// Mitsuba's GTR1 clear-coat distribution at `cos theta_h = 1`, in single
/// precision as Mitsuba computes it (`(a^2 - 1) / (pi ln(a^2) (1 + (a^2 - 1)
/// cos^2))`, `a = lerp(0.1, 0.001, gloss)`), and the same in double.
fn gtr1_at_normal(gloss: f64) -> (f64, f64) {
    let g32 = gloss as f32;
    let a32 = 0.1f32 + (0.001f32 - 0.1f32) * g32;
    let a2_32 = a32 * a32;
    let d32 = (a2_32 - 1.0) / (std::f32::consts::PI * a2_32.ln() * (1.0 + (a2_32 - 1.0)));
    let a = 0.1 + (0.001 - 0.1) * gloss;
    let a2 = a * a;
    let d64 = (a2 - 1.0) / (std::f64::consts::PI * a2.ln() * (1.0 + (a2 - 1.0)));
    (d32 as f64, d64)
}

/// At the normal (`H = N`) the glossy clear coat's `1 + (a^2 - 1) cos^2`
/// is `a^2 ~ 1.2e-4` (gloss 0.9) computed as a difference of numbers near
/// 1, so Mitsuba's single precision loses about four digits there: case 1
/// deviates 1.4e-4 at the normal. The deviation is exactly that rounding:
/// with the clear coat's `D` replaced by its single-precision value
/// (`clearcoat/4 F(0.04) D G`, `F = 0.04` and `G = 1` at the normal) every
/// case equals Mitsuba to 1e-6 there (observed: 5e-8 at most, from
/// 1.4e-4).
#[test]
fn deviation_at_the_normal_is_mitsubas_single_precision_clearcoat() {
    let fx = fixture();
    let n = [0.0, 0.0, 1.0];
    let mut explained = 0;
    for c in &fx.cases {
        let m = cases::build(&c.model, c.channels, c.lobes, &c.params);
        let f = ours(m.as_ref(), &n, &n);
        let coat = if c.model == "principled" {
            let names: Vec<&str> = m.param_specs().iter().map(|s| s.name.as_str()).collect();
            let get = |k: &str| c.params[names.iter().position(|&x| x == k).unwrap()];
            let (d32, d64) = gtr1_at_normal(get("clearcoat_gloss"));
            get("clearcoat") * 0.25 * 0.04 * (d32 - d64)
        } else {
            0.0
        };
        for k in 0..3 {
            let raw = rel(f[k], c.peak[k]);
            let corrected = rel(f[k] + coat, c.peak[k]);
            eprintln!(
                "{} ch {k}: at the normal {raw:.3e}, with single-precision GTR1 {corrected:.3e}",
                c.model
            );
            assert!(corrected <= 1e-6, "{}: {corrected}", c.model);
            if raw > 1e-4 {
                explained += 1;
            }
        }
    }
    // Case 1 (clearcoat 0.6, gloss 0.9): green and blue exceed 1e-4 before
    // the correction (red 9e-5).
    assert_eq!(explained, 2);
}
