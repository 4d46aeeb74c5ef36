//! Render a GGX-like BRDF and a rougher variant under every light set and
//! write the renders (PNG at `1 / p99`, EXR), the HDR-FLIP map (magma) and
//! the metrics:
//!
//! `cargo run --release -p brdf-render --example judge_images -- OUT_DIR`

use std::path::PathBuf;

use brdf_core::Brdf;
use brdf_render::flip::hdr_flip_map;
use brdf_render::light::LIGHT_SET_NAMES;
use brdf_render::tonemap::p99_exposure;
use brdf_render::{LightSet, RenderError, ShadingPoints, compare};
use nalgebra::Vector3;

/// Lambert plus a GGX lobe with Smith shadowing and Schlick Fresnel.
struct Ggx {
    kd: [f64; 3],
    alpha: f64,
    f0: f64,
}

impl Brdf for Ggx {
    fn channels(&self) -> usize {
        3
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let h = (l + v).normalize();
        let a2 = self.alpha * self.alpha;
        let d = a2 / (std::f64::consts::PI * (h.z * h.z * (a2 - 1.0) + 1.0).powi(2));
        let lambda = |c: f64| 0.5 * ((1.0 + a2 * (1.0 - c * c) / (c * c)).sqrt() - 1.0);
        let g = 1.0 / (1.0 + lambda(l.z) + lambda(v.z));
        let f = self.f0 + (1.0 - self.f0) * (1.0 - l.dot(&h)).powi(5);
        let spec = d * g * f / (4.0 * l.z * v.z);
        for c in 0..3 {
            out[c] = self.kd[c] / std::f64::consts::PI + spec;
        }
    }
}

fn main() -> Result<(), RenderError> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "judge_images".into()),
    );
    std::fs::create_dir_all(&out).map_err(|e| RenderError::Io {
        path: out.display().to_string(),
        source: e,
    })?;
    let reference = Ggx {
        kd: [0.5, 0.25, 0.1],
        alpha: 0.15,
        f0: 0.04,
    };
    let test = Ggx {
        kd: [0.45, 0.25, 0.12],
        alpha: 0.3,
        f0: 0.04,
    };
    for name in LIGHT_SET_NAMES {
        let lights = LightSet::parse(name)?;
        let sp = ShadingPoints::judge(&lights, 128);
        let (r, t) = (sp.render(&reference), sp.render(&test));
        let exposure = p99_exposure(&r, Some(&sp.mask()))?;
        r.write_png(&out.join(format!("{name}_ref.png")), exposure)?;
        t.write_png(&out.join(format!("{name}_test.png")), exposure)?;
        r.write_exr(&out.join(format!("{name}_ref.exr")))?;
        hdr_flip_map(&r, &t)?
            .to_magma()
            .write_png(&out.join(format!("{name}_flip.png")), 1.0)?;
        let e = compare(&reference, &test, &lights, 128)?;
        println!(
            "{name}: HDR-FLIP {:.4}, PSNR {:.2} dB, dE00 {:.3}, exposure {:.4}",
            e.flip, e.psnr, e.delta_e, e.exposure
        );
    }
    Ok(())
}
