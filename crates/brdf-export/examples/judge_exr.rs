//! Render a saved model with `brdf-render` on the judge sphere under each
//! light set (128 px, background shown) and write `OUT_DIR/LIGHT.exr`, for
//! `tests/reference/render_check.py` (run by `check_exports.sh`), which
//! renders the model's exports in Mitsuba and Blender Cycles and compares
//! them with these by HDR-FLIP:
//!
//! `cargo run --release -p brdf-export --example judge_exr -- MODEL.json OUT_DIR`

use std::path::PathBuf;

use brdf_models::saved_model::SavedModel;
use brdf_render::{LightSet, ShadingPoints};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [model, out] = args.as_slice() else {
        return Err("usage: judge_exr MODEL.json OUT_DIR".into());
    };
    let m = SavedModel::load(&PathBuf::from(model))?.build()?;
    let out = PathBuf::from(out);
    std::fs::create_dir_all(&out)?;
    for light in [LightSet::sky(), LightSet::studio()] {
        let img = ShadingPoints::judge_with_background(&light, 128).render(m.as_ref());
        img.write_exr(&out.join(format!("{}.exr", light.name())))?;
    }
    Ok(())
}
