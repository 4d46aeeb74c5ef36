//! Choose the smallest adequate model for a CUReT material: fit the
//! candidates, keep the one with the fewest stored numbers whose error is
//! within 5% of the best, and print the error-vs-size curve with AIC/BIC.
//!
//! `BRDF_DATA=path/to/data cargo run -p brdf-fit --example select_model`

use brdf_fit::FitOptions;
use brdf_fit::select::select;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let Ok(root) = std::env::var("BRDF_DATA") else {
        println!("BRDF_DATA is not set: skipped (it names the folder with curet/abrdf.dat)");
        return Ok(());
    };
    let samples = brdf_io::load(&format!("{root}/curet/abrdf.dat#61"))?;
    let (samples, _) = samples.filter_angle_limit(80f64.to_radians());
    let (rows, chosen) = select(&samples, 0.05, &FitOptions::default())?;
    for (k, r) in rows.iter().enumerate() {
        let mark = if k == chosen { "  <- chosen" } else { "" };
        println!(
            "{:<28} {:>3} numbers  L2 {:.5}{mark}",
            r.label, r.stored_numbers, r.error
        );
    }
    Ok(())
}
