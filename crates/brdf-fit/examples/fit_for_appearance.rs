//! Fit a renderer model to a measured film so that it *looks* like the
//! measurement: candidates under several objectives, chosen by their image
//! error under the standard light sets, refined in the image objective.
//!
//! `BRDF_DATA=path/to/data cargo run --release -p brdf-fit --example fit_for_appearance [MODEL] [FILE] [OUT.json]`

use brdf_fit::{FitRequest, Material, Metric};
use brdf_render::judge::REPORT_SIZE;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    if std::env::var_os("BRDF_DATA").is_none() {
        println!("BRDF_DATA is not set: skipped (it names the folder with rgl/)");
        return Ok(());
    }
    let mut args = std::env::args().skip(1);
    let model = args.next().unwrap_or_else(|| "ggx".into());
    let file = args
        .next()
        .unwrap_or_else(|| "cc_iris_purple_gem_rgb.bsdf".into());
    let spec = format!("rgl/{file}");
    let material = Material::load(&spec)?;
    let request = FitRequest {
        metric: Metric::Appearance,
        ..FitRequest::new(&material, brdf_fit::resolve(&model)?)
    };
    let report = request.run()?.into_report()?;
    for c in &report.candidates {
        println!(
            "{} {:<10} lobes {:<14} FLIP sky {:.3} studio {:.3}  dE {:.1}  Ngan L2 {:.4}  {:.2} s",
            if c.chosen { "*" } else { " " },
            c.objective,
            c.lobes.join("+"),
            c.image.lights[0].flip,
            c.image.lights[1].flip,
            c.image.max_delta_e(),
            c.ngan_l2,
            c.seconds
        );
    }
    let errors = report
        .image_error
        .as_ref()
        .ok_or("an RGL file is always judged")?;
    println!(
        "chosen at {REPORT_SIZE} px: mean FLIP {:.3}",
        errors.mean_flip()
    );
    for note in &report.notes {
        println!("note: {note}");
    }
    if let Some(out) = args.next() {
        report.saved_model(&spec)?.save(out.as_ref())?;
        println!("saved {out}");
    }
    Ok(())
}
