//! Evaluate a model from the catalogue and compute its directional albedo.
//!
//! `cargo run -p brdf-models --example albedo -- lambert 0.3`

use brdf_core::{AlbedoFrame, QuadratureOptions, directional_albedo, spherical_to_cartesian};
use brdf_models::{ModelConfig, build};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "lambert".to_string());
    let mut model = build(&name, &ModelConfig::default())?;
    // Remaining arguments override the parameters in order.
    let mut p = model.params().to_vec();
    for (slot, arg) in p.iter_mut().zip(args) {
        *slot = arg.parse()?;
    }
    model.set_params(&p)?;
    for deg in [0.0f64, 30.0, 60.0, 85.0] {
        let l = spherical_to_cartesian(deg.to_radians(), 0.0);
        let a = directional_albedo(
            model.as_ref(),
            &l,
            AlbedoFrame::Normal,
            &QuadratureOptions::default(),
        );
        println!(
            "theta_i = {deg:>4} deg: albedo {:.6} (error estimate {:.1e})",
            a.value[0], a.error[0]
        );
    }
    Ok(())
}
