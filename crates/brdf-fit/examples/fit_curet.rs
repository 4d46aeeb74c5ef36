//! Fit Blinn-Phong to a CUReT material (sample 25, as in Kurt's Table 9.2).
//!
//! `BRDF_DATA=path/to/data cargo run -p brdf-fit --example fit_curet`

use brdf_fit::{Channels, Fit};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let Ok(root) = std::env::var("BRDF_DATA") else {
        println!("BRDF_DATA is not set: skipped (it names the folder with curet/abrdf.dat)");
        return Ok(());
    };
    let samples = brdf_io::load(&format!("{root}/curet/abrdf.dat#25"))?;
    let report = Fit::model("Blinn-Phong")?
        .channels(Channels::Grey)
        .limit_deg(80.0)
        .run(&samples)?;
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
