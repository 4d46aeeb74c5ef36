//! Fit a thin film to a measured colour-shifting paint and write it as a
//! Blender material: the film's thickness and indices are fitted (from a
//! scan of the thickness) for appearance, and the script builds Cycles'
//! own thin film, which renders the fitted model exactly.
//!
//! `BRDF_DATA=path/to/data cargo run --release -p brdf-export --example thin_film_for_blender [FILE] [OUT.py]`

use brdf_export::{Target, export};
use brdf_fit::{FitRequest, Material};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    if std::env::var_os("BRDF_DATA").is_none() {
        println!("BRDF_DATA is not set: skipped (it names the folder with rgl/)");
        return Ok(());
    }
    let mut args = std::env::args().skip(1);
    let file = args
        .next()
        .unwrap_or_else(|| "cc_ibiza_sunset_rgb.bsdf".into());
    let material = Material::load(&format!("rgl/{file}"))?;
    // A renderer model on data that can be rendered: fitted for appearance.
    let request = FitRequest::new(&material, brdf_fit::resolve("film-cycles")?);
    let report = request.run()?.into_report()?;
    let m = report.model.as_ref();
    for (spec, value) in m.param_specs().iter().zip(m.params()) {
        println!("{:<9} {value:.4}  {}", spec.name, spec.meaning);
    }
    if let Some(errors) = &report.image_error {
        for l in &errors.lights {
            println!("HDR-FLIP under {}: {:.3}", l.light, l.flip);
        }
    }
    let script = export(report.model.as_ref(), Target::Blender)?;
    match args.next() {
        Some(out) => {
            std::fs::write(&out, script)?;
            println!("wrote {out}: blender -b -P {out} builds the material");
        }
        None => println!(
            "{} lines of Blender Python (give OUT.py to write them)",
            script.lines().count()
        ),
    }
    Ok(())
}
