//! Render saved models, or dense measurements, with `brdf-render` on the
//! judge sphere under each light set (128 px, background shown) and write
//! `OUT_DIR/LIGHT.exr` for each. For `tests/reference/render_check.py` (run
//! by `check_exports.sh`), which renders the model's exports in Mitsuba and
//! Blender Cycles and compares them with these by HDR-FLIP, and for the CI
//! judge (`benches/judge/test_judge.py`), which compares brdf-render's render
//! of each RGL measurement with Mitsuba's `measured` plugin's:
//!
//! `cargo run --release -p brdf-export --example judge_exr -- MODEL.json|DATA.bsdf OUT_DIR [MODEL.json|DATA.bsdf OUT_DIR ...]`
//!
//! Several pairs in one run share the judge's shading terms, which cost
//! more than a render (about a second per light set).

use std::path::PathBuf;

use brdf_core::Brdf;
use brdf_models::saved_model::SavedModel;
use brdf_render::{LightSet, ShadingPoints};

const USAGE: &str =
    "usage: judge_exr MODEL.json|DATA.bsdf OUT_DIR [MODEL.json|DATA.bsdf OUT_DIR ...]";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.is_empty() || !args.len().is_multiple_of(2) {
        return Err(USAGE.into());
    }
    // Every source is read before anything is rendered, so a bad one stops
    // the run before the long part.
    let jobs = args
        .chunks_exact(2)
        .map(|pair| Ok((load(&pair[0])?, PathBuf::from(&pair[1]))))
        .collect::<Result<Vec<_>, Box<dyn std::error::Error>>>()?;
    for (_, out) in &jobs {
        std::fs::create_dir_all(out)?;
    }
    for light in [LightSet::sky(), LightSet::studio()] {
        let terms = ShadingPoints::judge_with_background(&light, 128);
        for (brdf, out) in &jobs {
            let img = terms.render(brdf.as_ref());
            img.write_exr(&out.join(format!("{}.exr", light.name())))?;
        }
    }
    Ok(())
}

/// A saved model is JSON; anything else is read as dense data (MERL, RGL),
/// with the loader's own error for a file it cannot read.
fn load(source: &str) -> Result<Box<dyn Brdf>, Box<dyn std::error::Error>> {
    if source.ends_with(".json") {
        Ok(SavedModel::load(&PathBuf::from(source))?.build()?)
    } else {
        Ok(brdf_io::load_dense(source)?
            .ok_or_else(|| format!("{source}: not dense data (MERL .binary, RGL .bsdf)"))?)
    }
}
