//! Fit a renderer model to a measured film so that it *looks* like the
//! measurement: candidates under several objectives, chosen by their image
//! error under the standard light sets, refined in the image objective.
//!
//! `BRDF_DATA=path/to/data cargo run --release -p brdf-fit --example fit_for_appearance [MODEL] [FILE]`

use brdf_fit::Fit;
use brdf_fit::appearance::fit_for_appearance;
use brdf_render::judge::{Judge, REPORT_SIZE};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let Ok(root) = std::env::var("BRDF_DATA") else {
        println!("BRDF_DATA is not set: skipped (it names the folder with rgl/)");
        return Ok(());
    };
    let mut args = std::env::args().skip(1);
    let model = args.next().unwrap_or_else(|| "ggx".into());
    let file = args
        .next()
        .unwrap_or_else(|| "cc_iris_purple_gem_rgb.bsdf".into());
    let spec = format!("{root}/rgl/{file}");
    let samples = brdf_io::load(&spec)?;
    let Some(data) = brdf_io::load_dense(&spec)? else {
        return Err(format!("{spec}: not evaluable at any direction pair").into());
    };
    let (report, candidates) = fit_for_appearance(&Fit::model(&model)?, &samples, data.as_ref())?;
    for c in &candidates {
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
    let final_errors = Judge::new(REPORT_SIZE).errors(data.as_ref(), report.model.as_ref())?;
    println!(
        "chosen at {REPORT_SIZE} px: mean FLIP {:.3}",
        final_errors.mean_flip()
    );
    for w in final_errors.warnings() {
        println!("warning: {w}");
    }
    if let Some(out) = args.next() {
        report
            .saved_model(&format!("rgl/{file}"))?
            .save(out.as_ref())?;
        println!("saved {out}");
    }
    Ok(())
}
