//! `brdf render`: a labelled sphere of a saved model, dense data beside a
//! fit, and typed errors for bad input.

use crate::common;

use brdf_core::DirPairs;
use brdf_models::{ModelConfig, build};
use common::brdf;

fn decode(path: &std::path::Path) -> (usize, usize, Vec<u8>) {
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut r = dec.read_info().unwrap();
    let mut px = vec![0; r.output_buffer_size().unwrap()];
    let info = r.next_frame(&mut px).unwrap();
    (info.width as usize, info.height as usize, px)
}

fn lambert_file(dir: &std::path::Path) -> std::path::PathBuf {
    let mut m = build("lambert", &ModelConfig::default()).unwrap();
    m.set_params(&[0.5]).unwrap();
    let saved = brdf_study::saved_model::SavedModel::capture(
        m.as_ref(),
        &ModelConfig::default(),
        &DirPairs::with_capacity(0),
        None,
        &["y".to_string()],
        Default::default(),
    )
    .unwrap();
    let p = dir.join("lambert.json");
    saved.save(&p).unwrap();
    p
}

#[test]
fn a_lambert_sphere_lit_from_the_camera_is_radially_symmetric_and_labelled() {
    let dir = std::env::temp_dir().join(format!("brdf-render-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = lambert_file(&dir);
    let out = dir.join("s.png");
    let (ok, _, err) = brdf(&[
        "render",
        "--model",
        model.to_str().unwrap(),
        "--light",
        "0,0",
        "--size",
        "64",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let (w, _, px) = decode(&out);
    let grey = |x: usize, y: usize| {
        let o = (y * w + x) * 3;
        (px[o], px[o + 1], px[o + 2])
    };
    let h = px.len() / 3 / w;
    // The tile: its top-left corner is off the sphere, an 8 x 8 block of
    // pure black (no glyph of the labels is that large).
    let black = |x: usize, y: usize| grey(x, y) == (0, 0, 0);
    let (tx, ty) = (0..h - 10)
        .flat_map(|y| (0..w - 20).map(move |x| (x, y)))
        .find(|(x, y)| (0..8).all(|dy| (0..8).all(|dx| black(x + dx, y + dy))))
        .expect("no tile found");
    // Light and view along +z: f cos = kd/pi n.z is symmetric under x -> -x
    // and y -> -y, so the tile is its own mirror image, byte for byte.
    for y in 0..64 {
        for x in 0..64 {
            assert_eq!(
                grey(tx + x, ty + y),
                grey(tx + 63 - x, ty + y),
                "({x}, {y})"
            );
            assert_eq!(
                grey(tx + x, ty + y),
                grey(tx + x, ty + 63 - y),
                "({x}, {y})"
            );
        }
    }
    // Bright in the middle, black in the corners.
    assert!(grey(tx + 32, ty + 32).0 > 200 && black(tx, ty));
    let by = ty;
    // Some dark text was drawn above the tile (title and labels).
    assert!((0..by.saturating_sub(40)).any(|y| (0..w).any(|x| grey(x, y).0 < 80)));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_render_input_is_a_usage_error() {
    let dir = std::env::temp_dir().join(format!("brdf-render-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = lambert_file(&dir);
    let out = dir.join("x.png");
    let m = model.to_str().unwrap();
    let o = out.to_str().unwrap();
    for (args, word) in [
        (vec!["render", o], "--model"),
        (vec!["render", "--model", m, "--size", "5", o], "--size"),
        (
            vec!["render", "--model", m, "--light", "95,0", o],
            "--light",
        ),
        (
            vec!["render", "--model", "/nonexistent/m.json", o],
            "m.json",
        ),
    ] {
        let (ok, _, err) = brdf(&args);
        assert!(!ok && err.contains(word), "{args:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Scattered measurements (CUReT) cannot be drawn on a sphere: a usage
/// error saying so.
#[test]
#[ignore = "needs BRDF_DATA"]
fn rendering_scattered_data_is_a_usage_error() {
    let curet = common::data_file("curet/abrdf.dat");
    let dir = std::env::temp_dir().join(format!("brdf-render-scattered-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("x.png");
    let spec = format!("{}#25", curet.display());
    let (ok, _, err) = brdf(&["render", "--data", &spec, out.to_str().unwrap()]);
    assert!(!ok && err.contains("scattered"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn measured_and_fitted_side_by_side_with_a_difference() {
    let rgl = common::data_file("rgl/paper_white_rgb.bsdf");
    let dir = std::env::temp_dir().join(format!("brdf-render-pair-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("fit.json");
    let (ok, _, err) = brdf(&[
        "fit",
        "--model",
        "lambert",
        "--channels",
        "rgb",
        "--data",
        rgl.to_str().unwrap(),
        "--save",
        model.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let out = dir.join("pair.png");
    let (ok, _, err) = brdf(&[
        "render",
        "--model",
        model.to_str().unwrap(),
        "--data",
        rgl.to_str().unwrap(),
        "--size",
        "48",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let (w, _, _) = decode(&out);
    assert!(w >= 3 * 48, "three tiles side by side: width {w}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `brdf render` draws by default the sphere Python's `Model.render()`
/// draws and the reports judge: the judge's camera under the studio light
/// set at the reports' size (the EXR holds it as f32).
#[test]
fn the_default_sphere_is_the_judge_sphere() {
    let dir = std::env::temp_dir().join(format!("brdf-render-judge-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = lambert_file(&dir);
    let out = dir.join("s.exr");
    let (ok, _, err) = brdf(&[
        "render",
        "--model",
        model.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let written = brdf_render::Image::read_exr(&out).unwrap();
    let mut m = build("lambert", &ModelConfig::default()).unwrap();
    m.set_params(&[0.5]).unwrap();
    let size = brdf_render::judge::REPORT_SIZE;
    let judge =
        brdf_render::shading::render_judge(m.as_ref(), &brdf_render::LightSet::studio(), size);
    assert_eq!((written.width, written.height), (size, size));
    let mut lit = 0;
    for y in 0..size {
        for x in 0..size {
            for c in 0..3 {
                let want = judge.data[(y * size + x) * judge.channels + c.min(judge.channels - 1)];
                let got = written.data[(y * size + x) * written.channels + c];
                assert!(
                    (got - want).abs() <= 1e-6 * want.abs() + 1e-12,
                    "({x}, {y}, {c}): {got} vs {want}"
                );
                lit += usize::from(want > 0.0);
            }
        }
    }
    assert!(lit > size * size, "the sphere is lit");
    std::fs::remove_dir_all(&dir).unwrap();
}
