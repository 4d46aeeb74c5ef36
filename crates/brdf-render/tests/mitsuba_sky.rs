//! brdf-render against Mitsuba 3.9.1 in the judge scene: BSDFs whose
//! formulas Mitsuba and this test share exactly, rendered by Mitsuba
//! (`tests/reference/make_mitsuba_renders.py`, 1024 samples per pixel, the
//! EXRs committed beside it) and by [`ShadingPoints`], compared by HDR-FLIP
//! with Mitsuba as the reference.
//!
//! Why: the fit pipeline's image objective renders here while the judge
//! renders in Mitsuba; a light set that differs between the two makes the
//! objective optimise the wrong picture (the CIE clear-sky stand-in that
//! preceded the tabulated `sunsky` was at HDR-FLIP 0.50 from Mitsuba).
//! The bound [`SKY_BOUND`] sits above Mitsuba's own noise (the reference
//! against itself at another seed: 0.010-0.014, `mitsuba_renders.json`)
//! plus the quadrature error of the environment's cells
//! (`brdf_render::quadrature`).

use std::f64::consts::PI;
use std::path::PathBuf;

use brdf_core::Brdf;
use brdf_render::flip::hdr_flip;
use brdf_render::{Image, LightSet, RenderError, ShadingPoints};
use nalgebra::Vector3;

/// Largest HDR-FLIP of a brdf-render render against Mitsuba's.
const SKY_BOUND: f64 = 0.05;

/// Mitsuba's `blendbsdf` of `diffuse` (weight `1 - w`) and a GGX
/// `roughconductor` with `material = none` (Fresnel 1) and separable Smith
/// shadowing (weight `w`); `w = 0` is plain `diffuse`.
struct DiffuseGgx {
    kd: [f64; 3],
    w: f64,
    alpha: f64,
}

impl Brdf for DiffuseGgx {
    fn channels(&self) -> usize {
        3
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        if l.z <= 0.0 || v.z <= 0.0 {
            out.fill(0.0);
            return;
        }
        let spec = if self.w > 0.0 {
            let h = (l + v).normalize();
            let a2 = self.alpha * self.alpha;
            let d = a2 / (PI * (h.z * h.z * (a2 - 1.0) + 1.0).powi(2));
            let g1 = |w: &Vector3<f64>| {
                let c2 = w.z * w.z;
                2.0 / (1.0 + (1.0 + a2 * (1.0 - c2) / c2).sqrt())
            };
            d * g1(l) * g1(v) / (4.0 * l.z * v.z)
        } else {
            0.0
        };
        for c in 0..3 {
            out[c] = (1.0 - self.w) * self.kd[c] / PI + self.w * spec;
        }
    }
}

fn case(name: &str) -> DiffuseGgx {
    match name {
        "lambert" => DiffuseGgx {
            kd: [0.8, 0.6, 0.4],
            w: 0.0,
            alpha: 0.0,
        },
        "glossy" => DiffuseGgx {
            kd: [0.2, 0.4, 0.7],
            w: 0.3,
            alpha: 0.15,
        },
        _ => DiffuseGgx {
            kd: [0.2, 0.4, 0.7],
            w: 0.3,
            alpha: 0.05,
        },
    }
}

fn reference(file: &str) -> Result<Image, RenderError> {
    let path: PathBuf = [env!("CARGO_MANIFEST_DIR"), "tests", "reference", file]
        .iter()
        .collect();
    Image::read_exr(&path)
}

fn flip_against_mitsuba(name: &str, light: &str) -> Result<f64, RenderError> {
    let mitsuba = reference(&format!("{name}.{light}.exr"))?;
    let ours =
        ShadingPoints::judge_with_background(&LightSet::parse(light)?, 128).render(&case(name));
    hdr_flip(&mitsuba, &ours)
}

#[test]
fn sky_renders_match_mitsuba() -> Result<(), RenderError> {
    for name in ["lambert", "glossy", "sharp"] {
        let f = flip_against_mitsuba(name, "sky")?;
        println!("{name} under sky: HDR-FLIP {f:.4} against Mitsuba");
        assert!(f <= SKY_BOUND, "{name}: HDR-FLIP {f} > {SKY_BOUND}");
    }
    Ok(())
}

#[test]
fn studio_render_matches_mitsuba() -> Result<(), RenderError> {
    let f = flip_against_mitsuba("glossy", "studio")?;
    println!("glossy under studio: HDR-FLIP {f:.4} against Mitsuba");
    assert!(f <= SKY_BOUND, "HDR-FLIP {f} > {SKY_BOUND}");
    Ok(())
}

/// The comparison can fail: a body colour 15% darker, or the light from
/// the mirrored side, is far above the bound.
#[test]
fn a_wrong_colour_or_light_exceeds_the_bound() -> Result<(), RenderError> {
    let mitsuba = reference("lambert.sky.exr")?;
    let sp = ShadingPoints::judge_with_background(&LightSet::sky(), 128);
    let darker = sp.render(&DiffuseGgx {
        kd: [0.68, 0.51, 0.34],
        w: 0.0,
        alpha: 0.0,
    });
    let f = hdr_flip(&mitsuba, &darker)?;
    assert!(f > 2.0 * SKY_BOUND, "darker: {f}");
    let mut mirrored = sp.render(&case("lambert"));
    let n = mirrored.width;
    let flipped: Vec<f64> = (0..n * n)
        .flat_map(|p| {
            let (y, x) = (p / n, p % n);
            let q = y * n + (n - 1 - x);
            mirrored.data[q * 3..q * 3 + 3].to_vec()
        })
        .collect();
    mirrored.data = flipped;
    let f = hdr_flip(&mitsuba, &mirrored)?;
    assert!(f > 2.0 * SKY_BOUND, "mirrored: {f}");
    Ok(())
}

#[test]
fn zz_dump() -> Result<(), RenderError> {
    let dir = std::env::var("DUMP").unwrap_or_default();
    if dir.is_empty() {
        return Ok(());
    }
    for (name, light) in [("glossy", "studio"), ("sharp", "sky"), ("lambert", "sky")] {
        let ours =
            ShadingPoints::judge_with_background(&LightSet::parse(light)?, 128).render(&case(name));
        ours.write_exr(&PathBuf::from(format!("{dir}/{name}.{light}.exr")))?;
    }
    Ok(())
}
