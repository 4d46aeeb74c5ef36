//! Fit Ashikhmin-Shirley in RGB to an RGL material and save it.
//!
//! `BRDF_DATA=path/to/data cargo run -p brdf-fit --example fit_rgl_save [OUT.json]`

use brdf_fit::{FitRequest, Material, Metric, Objective};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    if std::env::var_os("BRDF_DATA").is_none() {
        println!("BRDF_DATA is not set: skipped (it names the folder with rgl/)");
        return Ok(());
    }
    let out = std::env::args().nth(1).unwrap_or_else(|| {
        std::env::temp_dir()
            .join("paper_white_as.json")
            .display()
            .to_string()
    });
    let spec = "rgl/paper_white_rgb.bsdf";
    let material = Material::load(spec)?;
    let request = FitRequest {
        metric: Metric::Objective(Objective::Ngan),
        starts: 12,
        ..FitRequest::new(&material, brdf_fit::resolve("ashikhmin_shirley")?)
    };
    let report = request.run()?.into_report()?;
    let image = report
        .image_error
        .as_ref()
        .ok_or("an RGL file is always judged")?;
    println!(
        "{}: Ngan L2 {:.5}, mean image FLIP {:.3} in {:.2} s ({})",
        report.summary.model,
        report.summary.ngan_l2,
        image.mean_flip(),
        report.summary.seconds,
        report.summary.solver
    );
    report.saved_model(spec)?.save(out.as_ref())?;
    println!("saved {out}");
    Ok(())
}
