//! Load a saved model (or fit one when no file is given) and render a lit
//! sphere to a PPM image: only `brdf-models` is needed to load and evaluate.
//!
//! `cargo run -p brdf-fit --example render_sphere [MODEL.json] [OUT.ppm]`

use std::io::Write;

use brdf_core::Brdf;
use brdf_models::saved_model::SavedModel;
use nalgebra::Vector3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let model: Box<dyn Brdf> = match args.first() {
        Some(path) => SavedModel::load_model(path.as_ref())?,
        None => {
            let text = r#"{ "schema": "brdf-fit/saved-model", "version": 1,
              "model": "blinn-phong", "structure": { "channels": 1 },
              "parameters": [ { "name": "kd", "value": 0.4 }, { "name": "ks", "value": 0.3 },
                              { "name": "n", "value": 40.0 } ] }"#;
            SavedModel::from_json(text, "built-in example")?.build()?
        }
    };
    let out = args.get(1).cloned().unwrap_or_else(|| {
        std::env::temp_dir()
            .join("sphere.ppm")
            .display()
            .to_string()
    });
    let size = 128;
    let light = Vector3::new(0.4, 0.3, 1.0).normalize();
    let view = Vector3::z();
    let nc = model.channels();
    let mut f = vec![0.0; nc];
    let mut pixels = Vec::with_capacity(size * size * 3);
    for y in 0..size {
        for x in 0..size {
            let (u, v) = (
                2.0 * (x as f64 + 0.5) / size as f64 - 1.0,
                1.0 - 2.0 * (y as f64 + 0.5) / size as f64,
            );
            let r2 = u * u + v * v;
            let mut rgb = [0.0; 3];
            if r2 < 1.0 {
                let n = Vector3::new(u, v, (1.0 - r2).sqrt());
                // Local frame around the normal.
                let t = n.cross(&Vector3::y()).normalize();
                let b = n.cross(&t);
                let to_local = |w: &Vector3<f64>| Vector3::new(w.dot(&t), w.dot(&b), w.dot(&n));
                let (l, vv) = (to_local(&light), to_local(&view));
                model.eval(&l, &vv, &mut f);
                for c in 0..3 {
                    rgb[c] = f[c.min(nc - 1)] * l.z.max(0.0) * std::f64::consts::PI;
                }
            }
            // sRGB-like display transfer, exposure 1.
            pixels.extend(rgb.map(|x| (255.0 * x.clamp(0.0, 1.0).powf(1.0 / 2.2)) as u8));
        }
    }
    let mut file = std::fs::File::create(&out)?;
    write!(file, "P6\n{size} {size}\n255\n")?;
    file.write_all(&pixels)?;
    println!("wrote {out} ({size}x{size}, exposure 1, gamma 2.2)");
    Ok(())
}
