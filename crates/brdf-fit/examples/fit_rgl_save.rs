//! Fit Ashikhmin-Shirley in RGB to an RGL material and save it.
//!
//! `BRDF_DATA=path/to/data cargo run -p brdf-fit --example fit_rgl_save [OUT.json]`

use brdf_fit::Fit;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let Ok(root) = std::env::var("BRDF_DATA") else {
        println!("BRDF_DATA is not set: skipped (it names the folder with rgl/)");
        return Ok(());
    };
    let out = std::env::args().nth(1).unwrap_or_else(|| {
        std::env::temp_dir()
            .join("paper_white_as.json")
            .display()
            .to_string()
    });
    let samples = brdf_io::load(&format!("{root}/rgl/paper_white_rgb.bsdf"))?;
    let report = Fit::model("ashikhmin_shirley")?.starts(12).run(&samples)?;
    println!(
        "{}: Ngan L2 {:.5} in {:.2} s ({})",
        report.summary.model, report.summary.ngan_l2, report.summary.seconds, report.summary.solver
    );
    report
        .saved_model("rgl/paper_white_rgb.bsdf")?
        .save(out.as_ref())?;
    println!("saved {out}");
    Ok(())
}
