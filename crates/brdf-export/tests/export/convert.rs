//! Conversion by fitting: the sampled pairs, and a source the target can
//! represent exactly is recovered (the conversion error is then ~0).

use brdf_core::Parametric;
use brdf_export::convert::{ConvertOptions, convert, sample_source};
use brdf_export::{Target, export};

fn model(name: &str, p: &[f64]) -> Box<dyn Parametric> {
    let mut m = brdf_models::build(name, &Default::default()).unwrap();
    m.set_params(p).unwrap();
    m
}

#[test]
fn sampled_pairs_lie_inside_the_limit_and_are_deterministic() {
    let m = model("blinn-phong", &[0.5, 0.2, 30.0]);
    let opts = ConvertOptions {
        pairs: 500,
        limit_deg: 60.0,
        ..Default::default()
    };
    let a = sample_source(m.as_ref(), &opts).unwrap();
    assert_eq!(a.len(), 500);
    let c = 60f64.to_radians().cos();
    for j in 0..a.len() {
        let (l, v) = (a.pairs().l(j), a.pairs().v(j));
        assert!(l.z >= c && v.z >= c);
        assert!(((l.norm() - 1.0).abs() < 1e-12) && ((v.norm() - 1.0).abs() < 1e-12));
    }
    // Half of the pairs near the mirror direction (theta_h < 22.5 deg), as
    // the warp theta_h = pi/2 u^2 intends.
    let near = (0..a.len())
        .filter(|&j| (a.pairs().l(j) + a.pairs().v(j)).normalize().z > 22.5f64.to_radians().cos())
        .count();
    assert!(near > 200, "{near}");
    assert_eq!(sample_source(m.as_ref(), &opts).unwrap(), a);
}

/// A Lambert + GGX dielectric lobe with a grey `ks` and `kd <= 1 - ks` is a
/// pbrt-v4 mix: fitting the mix to it recovers it.
#[test]
fn a_representable_source_is_recovered() {
    // kd, ks, alpha, eta
    let src = model("ggx-dielectric", &[0.4, 0.3, 0.2, 1.6]);
    let opts = ConvertOptions {
        pairs: 400,
        starts: 4,
        ..Default::default()
    };
    let c = convert(src.as_ref(), Target::Pbrt, &opts).unwrap();
    assert_eq!(c.model.name(), "ggx-dielectric");
    assert!(c.error.relative_l2 < 1e-6, "{:?}", c.error);
    for (a, b) in c.model.params().iter().zip(src.params()) {
        assert!(
            (a - b).abs() < 1e-4,
            "{:?} vs {:?}",
            c.model.params(),
            src.params()
        );
    }
    // The converted model is written exactly.
    assert!(export(c.model.as_ref(), Target::Pbrt).is_ok());
}

fn paper_white_ggx() -> Box<dyn Parametric> {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/reference/paper_white/ggx.json");
    let saved = brdf_models::saved_model::SavedModel::load(&path).unwrap();
    saved.build().unwrap()
}

/// Quick options: fewer pairs and starts, the judge at 64 pixels.
fn quick() -> ConvertOptions {
    ConvertOptions {
        pairs: 1024,
        starts: 4,
        judge_size: 64,
        ..Default::default()
    }
}

/// The paper_white GGX fit (height-correlated, no Mitsuba equivalent)
/// converted to Mitsuba's principled for appearance renders close to the
/// source (mean HDR-FLIP below 0.03, the colour kept) but changes the sky
/// render by more than the 0.02 the appearance fits aim at (the committed 128-pixel report:
/// 0.027; Burley's diffuse is not GGX's Lambert), so the export refuses it
/// and names the better route.
#[test]
fn ggx_to_principled_is_close_but_beyond_the_bound() {
    use brdf_export::convert::{DELTA_E_WARN, FLIP_REFUSE, FLIP_WARN};
    let src = paper_white_ggx();
    let c = convert(src.as_ref(), Target::Mitsuba, &quick()).unwrap();
    assert_eq!(c.model.name(), "principled");
    assert!(c.appearance);
    eprintln!("{}", brdf_export::convert::image_note(&c.image));
    assert!(c.image.mean_flip() < 0.03, "{:?}", c.image);
    assert!(c.image.max_flip() > FLIP_WARN, "{:?}", c.image);
    assert!(c.image.max_flip() < FLIP_REFUSE, "{:?}", c.image);
    assert!(c.image.max_delta_e() < DELTA_E_WARN);
    // Written, with a warning naming the renderer's own route.
    c.check(Target::Mitsuba).expect("below the refusal limits");
    use brdf_export::for_renderer::conversion_warning;
    let warning =
        conversion_warning(&c, Target::Mitsuba, brdf_export::FrontEnd::Cli).expect("beyond 0.02");
    assert!(
        warning.contains("`brdf fit --data DATA --for mitsuba --out FILE`"),
        "{warning}"
    );
    let py = conversion_warning(&c, Target::Mitsuba, brdf_export::FrontEnd::Python)
        .expect("beyond 0.02");
    assert!(
        py.contains("for_renderer=\"mitsuba\"") && !py.contains("--"),
        "{py}"
    );
    assert!(c.note().contains("HDR-FLIP"), "{}", c.note());
}

/// A glossy GGX converted to a Lambert (`via`) loses its highlight: the
/// export is refused with an error naming the better route, and written
/// with `force`, its image error in the file.
#[test]
fn a_conversion_that_changes_the_look_is_refused_unless_forced() {
    // kd, ks, alpha, f0: a dark base under a bright sharp highlight
    let src = model("ggx", &[0.05, 1.0, 0.05, 1.0]);
    let opts = ConvertOptions {
        via: Some("lambert".into()),
        ..quick()
    };
    let e = brdf_export::export_or_convert(src.as_ref(), Target::Gltf, &opts)
        .err()
        .expect("refused");
    let msg = e.to_string();
    assert!(
        matches!(e, brdf_export::ExportError::LooksDifferent { .. }),
        "{msg}"
    );
    assert!(
        msg.contains("fit the target's model directly: `brdf fit --model lambert")
            && msg.contains("--force"),
        "{msg}"
    );
    let forced = ConvertOptions {
        force: true,
        ..opts
    };
    let done = brdf_export::export_or_convert(src.as_ref(), Target::Gltf, &forced).unwrap();
    let c = done.conversion.expect("converted");
    assert!(c.image.max_flip() > brdf_export::convert::FLIP_REFUSE);
    assert!(done.text.contains("HDR-FLIP"), "{}", done.text);
    assert!(
        done.warnings
            .iter()
            .any(|w| w.contains("renders differently")),
        "{:?}",
        done.warnings
    );
}
