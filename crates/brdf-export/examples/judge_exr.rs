//! Render a saved model, or a dense measurement, with `brdf-render` on the
//! judge sphere under each light set (128 px, background shown) and write
//! `OUT_DIR/LIGHT.exr`. For `tests/reference/render_check.py` (run by
//! `check_exports.sh`), which renders the model's exports in Mitsuba and
//! Blender Cycles and compares them with these by HDR-FLIP, and for the CI
//! judge (`benches/judge/test_judge.py`), which compares brdf-render's render
//! of each RGL measurement with Mitsuba's `measured` plugin's:
//!
//! `cargo run --release -p brdf-export --example judge_exr -- MODEL.json|DATA.bsdf OUT_DIR`

use std::path::PathBuf;

use brdf_core::Brdf;
use brdf_models::saved_model::SavedModel;
use brdf_render::{LightSet, ShadingPoints};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [source, out] = args.as_slice() else {
        return Err("usage: judge_exr MODEL.json|DATA.bsdf OUT_DIR".into());
    };
    // A saved model is JSON; anything else is read as dense data (MERL,
    // RGL), with the loader's own error for a file it cannot read.
    let brdf: Box<dyn Brdf> = if source.ends_with(".json") {
        SavedModel::load(&PathBuf::from(source))?.build()?
    } else {
        brdf_io::load_dense(source)?
            .ok_or_else(|| format!("{source}: not dense data (MERL .binary, RGL .bsdf)"))?
    };
    let out = PathBuf::from(out);
    std::fs::create_dir_all(&out)?;
    for light in [LightSet::sky(), LightSet::studio()] {
        let img = ShadingPoints::judge_with_background(&light, 128).render(brdf.as_ref());
        img.write_exr(&out.join(format!("{}.exr", light.name())))?;
    }
    Ok(())
}
