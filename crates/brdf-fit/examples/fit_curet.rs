//! Fit Blinn-Phong to a CUReT material (sample 25, as in Kurt's Table 9.2).
//!
//! `BRDF_DATA=path/to/data cargo run -p brdf-fit --example fit_curet`

use brdf_fit::{ChannelMode, FitRequest, Material};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    if std::env::var_os("BRDF_DATA").is_none() {
        println!("BRDF_DATA is not set: skipped (it names the folder with curet/abrdf.dat)");
        return Ok(());
    }
    // Relative paths are read under BRDF_DATA.
    let material = Material::load("curet/abrdf.dat#25")?;
    let request = FitRequest {
        channels: ChannelMode::Grey,
        limit_deg: 80.0,
        ..FitRequest::new(&material, brdf_fit::resolve("Blinn-Phong")?)
    };
    let report = request.run()?.into_report()?;
    let s = &report.summary;
    println!(
        "{} on {}: {} of {} samples, Ngan L2 {:.5}, {}",
        s.model, s.data, s.samples, report.samples_present, s.ngan_l2, s.termination
    );
    for p in &s.parameters {
        println!("  {:<4} = {:.6}", p.name, p.value);
    }
    Ok(())
}
