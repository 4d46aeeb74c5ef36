//! The judge renderer against independent references: analytic Lambert
//! shading, the constant-environment furnace, reciprocity, FLIP and the
//! comparison of a model with itself.

use brdf_core::Brdf;
use brdf_render::camera::Camera;
use brdf_render::flip::{hdr_flip, ldr_flip};
use brdf_render::scene::sphere_hits;
use brdf_render::{Image, LightSet, RenderError, ShadingPoints, compare};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// Lambert, grey or RGB.
struct Lambert(Vec<f64>);
impl Brdf for Lambert {
    fn channels(&self) -> usize {
        self.0.len()
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        for (o, kd) in out.iter_mut().zip(&self.0) {
            *o = if l.z > 0.0 && v.z > 0.0 { kd / PI } else { 0.0 };
        }
    }
}

/// A non-reciprocal test BRDF: depends on `l.z` and `v.z` unequally.
struct Skewed;
impl Brdf for Skewed {
    fn channels(&self) -> usize {
        1
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        out[0] = 0.3 + l.z * l.z * 0.5 + 0.1 * v.z;
    }
}

#[test]
fn lambert_under_a_directional_light_is_kd_cos_over_pi() -> Result<(), RenderError> {
    let dir = Vector3::new(0.3, 0.6, 0.7).normalize();
    let lights = LightSet::directional(dir)?;
    let img = ShadingPoints::judge(&lights, 48).render(&Lambert(vec![0.2, 0.5, 0.8]));
    let hits = sphere_hits(&Camera::judge(), 48);
    assert!(hits.len() > 1000);
    for h in &hits {
        let cos = h.point.dot(&dir).max(0.0);
        for (c, kd) in [0.2, 0.5, 0.8].iter().enumerate() {
            let expect = kd / PI * cos;
            assert!((img.data[h.pixel * 3 + c] - expect).abs() < 1e-14);
        }
    }
    // Off the sphere: black.
    assert_eq!(img.data[0], 0.0);
    Ok(())
}

#[test]
fn lambert_in_a_constant_environment_is_kd_times_radiance() {
    // The studio's surround alone: 0.05 from every direction, so every
    // sphere pixel is kd * 0.05 (the cosine-weighted hemisphere integral of
    // a constant is pi); this checks the quadrature's weights.
    let env = brdf_render::environment::Environment::constant([0.05; 3]);
    let lights = LightSet::Studio {
        surround: env,
        key: brdf_render::area_light::SquareLight::look_at(
            Vector3::new(3.0, 3.0, 4.0),
            Vector3::zeros(),
            Vector3::y(),
            1.2,
            [0.0; 3],
            1,
        ),
    };
    let sp = ShadingPoints::judge(&lights, 32);
    let img = sp.render(&Lambert(vec![0.7]));
    for p in &sp.pixels {
        let v = img.data[p.pixel * 3];
        assert!(
            (v / (0.7 * 0.05) - 1.0).abs() < 2e-3,
            "pixel {}: {v}",
            p.pixel
        );
        assert_eq!(img.data[p.pixel * 3 + 1], v);
    }
}

#[test]
fn reciprocal_brdfs_render_the_same_swapped_and_others_do_not() {
    let sp = ShadingPoints::judge(&LightSet::studio(), 24);
    let lam = Lambert(vec![0.4]);
    assert_eq!(sp.render(&lam), sp.render_swapped(&lam));
    assert_ne!(sp.render(&Skewed), sp.render_swapped(&Skewed));
}

/// A BRDF is evaluated as renderers evaluate it, the camera's direction
/// first (Mitsuba's `measured` plugin looks an RGL table up so): a pixel of
/// a non-reciprocal BRDF under one directional light is `f(v, l) n . l`.
#[test]
fn renders_evaluate_the_camera_direction_first() -> Result<(), RenderError> {
    let dir = Vector3::new(0.2, 0.5, 0.8).normalize();
    let sp = ShadingPoints::judge(&LightSet::directional(dir)?, 16);
    let img = sp.render(&Skewed);
    let swapped = sp.render_swapped(&Skewed);
    let mut f = [0.0];
    for t in sp.terms() {
        Skewed.eval(&t.v_local, &t.l_local, &mut f);
        let camera_first = f[0] * t.l_local.z;
        Skewed.eval(&t.l_local, &t.v_local, &mut f);
        let light_first = f[0] * t.l_local.z;
        assert!((img.data[t.pixel * 3] - camera_first).abs() <= 1e-12);
        assert!((swapped.data[t.pixel * 3] - light_first).abs() <= 1e-12);
    }
    Ok(())
}

#[test]
fn terms_reproduce_the_render() {
    let sp = ShadingPoints::judge(&LightSet::sky(), 20);
    let brdf = Lambert(vec![0.1, 0.2, 0.3]);
    let img = sp.render(&brdf);
    let mut acc = vec![0.0; 20 * 20 * 3];
    let mut f = [0.0; 3];
    for t in sp.terms() {
        assert!(t.l_local.z > 0.0 && t.v_local.z > 0.0);
        brdf.eval(&t.v_local, &t.l_local, &mut f);
        for c in 0..3 {
            acc[t.pixel * 3 + c] += t.weight[c] * f[c];
        }
    }
    for (a, b) in acc.iter().zip(&img.data) {
        assert!((a - b).abs() <= 1e-12 * b.abs().max(1e-300));
    }
}

fn noisy(img: &Image, amp: f64) -> Image {
    // A fixed pseudo-random pattern (xorshift), multiplicative.
    let mut s: u64 = 0x9E3779B97F4A7C15;
    let data = img
        .data
        .iter()
        .map(|v| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let u = (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            v * (1.0 + amp * u)
        })
        .collect();
    Image {
        data,
        ..img.clone()
    }
}

#[test]
fn flip_is_zero_against_itself_and_grows_with_noise() -> Result<(), RenderError> {
    let img = ShadingPoints::judge(&LightSet::studio(), 64).render(&Lambert(vec![0.6, 0.4, 0.3]));
    let mask = ShadingPoints::judge(&LightSet::studio(), 64).mask();
    let exposure = brdf_render::tonemap::p99_exposure(&img, Some(&mask))?;
    assert_eq!(ldr_flip(&img, &img, exposure)?, 0.0);
    assert_eq!(hdr_flip(&img, &img)?, 0.0);
    let (a, b) = (noisy(&img, 0.1), noisy(&img, 0.6));
    let (la, lb) = (ldr_flip(&img, &a, exposure)?, ldr_flip(&img, &b, exposure)?);
    let (ha, hb) = (hdr_flip(&img, &a)?, hdr_flip(&img, &b)?);
    assert!(0.0 < la && la < lb, "{la} {lb}");
    assert!(0.0 < ha && ha < hb, "{ha} {hb}");
    Ok(())
}

#[test]
fn compare_a_model_with_itself_and_with_a_darker_one() -> Result<(), RenderError> {
    let a = Lambert(vec![0.5, 0.4, 0.3]);
    let same = compare(&a, &a, &LightSet::sky(), 32)?;
    assert_eq!(same.flip, 0.0);
    assert_eq!(same.psnr, f64::INFINITY);
    assert_eq!(same.delta_e, 0.0);
    let darker = compare(&a, &Lambert(vec![0.4, 0.32, 0.24]), &LightSet::sky(), 32)?;
    assert!(darker.flip > 0.0 && darker.psnr.is_finite() && darker.delta_e > 1.0);
    assert!((darker.mean_colour_fit[0] / darker.mean_colour_data[0] - 0.8).abs() < 1e-12);
    assert!(compare(&a, &a, &LightSet::sky(), 1).is_err());
    Ok(())
}

#[test]
fn the_background_shows_the_environment() {
    let studio =
        ShadingPoints::judge_with_background(&LightSet::studio(), 16).render(&Lambert(vec![0.5]));
    assert!(studio.data[0..3].iter().all(|v| (v - 0.05).abs() < 1e-15));
    // The judge camera looks down from the sky's zenith (+z): every ray that
    // misses the sphere goes below the horizon, to Mitsuba's black ground.
    let sp = ShadingPoints::judge_with_background(&LightSet::sky(), 16);
    let sky = sp.render(&Lambert(vec![0.5]));
    assert_eq!(&sky.data[0..3], &[0.0; 3]);
    assert_eq!(&sky.data[(16 * 16 - 1) * 3..], &[0.0; 3]);
    // A camera looking at the horizon sees blue sky in its top row and the
    // ground in its bottom row.
    let camera = Camera::look_at(
        Vector3::new(0.0, -6.0, 0.0),
        Vector3::zeros(),
        Vector3::z(),
        22.0,
    )
    .expect("a valid camera");
    let side = ShadingPoints::new(&camera, &LightSet::sky(), 16)
        .with_background(&camera, &LightSet::sky())
        .render(&Lambert(vec![0.5]));
    assert!(side.data[2] > side.data[0] && side.data[0] > 0.0);
    assert_eq!(&side.data[(16 * 16 - 1) * 3..], &[0.0; 3]);
    // Without the background the same pixels are black; sphere pixels agree.
    let plain = ShadingPoints::new(&camera, &LightSet::sky(), 16).render(&Lambert(vec![0.5]));
    assert_eq!(plain.data[2], 0.0);
    let sp = ShadingPoints::new(&camera, &LightSet::sky(), 16);
    for p in &sp.pixels {
        assert_eq!(plain.data[p.pixel * 3], side.data[p.pixel * 3]);
    }
}

#[test]
fn renders_do_not_depend_on_the_thread_count() -> Result<(), rayon::ThreadPoolBuildError> {
    let brdf = Skewed;
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let three = rayon::ThreadPoolBuilder::new().num_threads(3).build()?;
    let a = one.install(|| ShadingPoints::judge(&LightSet::studio(), 40));
    let b = three.install(|| ShadingPoints::judge(&LightSet::studio(), 40));
    assert_eq!(a, b);
    assert_eq!(
        one.install(|| a.render(&brdf)),
        three.install(|| a.render(&brdf))
    );
    Ok(())
}

/// The mean-colour CIEDE2000 against the judge's own (colour-science,
/// `tests/reference/make_delta_e.py`): both colours scaled so the
/// reference's luminance is 0.5, negative channels clipped.
#[test]
fn mean_colour_delta_e_is_the_judges() {
    let text = include_str!("reference/delta_e_judge.json");
    let cases: serde_json::Value = serde_json::from_str(text).expect("JSON");
    let rgb = |v: &serde_json::Value| -> [f64; 3] {
        let a = v.as_array().expect("array");
        [0, 1, 2].map(|i| a[i].as_f64().expect("number"))
    };
    let cases = cases.as_array().expect("cases");
    assert_eq!(cases.len(), 4);
    for case in cases {
        let (r, t) = (rgb(&case["reference"]), rgb(&case["test"]));
        let want = case["delta_e"].as_f64().expect("number");
        let got = brdf_render::colour::delta_e_mean_colours(r, t);
        assert!(
            (got - want).abs() < 1e-3 * want.max(1.0),
            "{r:?} {t:?}: {got} against {want}"
        );
    }
}
