//! Texts the front ends print come from the code: the conversion limits
//! in `--list`, the options a refused conversion's advice names (the
//! command line's or Python's), the warning for a grey fit.

use brdf_export::convert::{DELTA_E_REFUSE, DELTA_E_WARN, FLIP_REFUSE, FLIP_WARN};
use brdf_export::{ExportError, FrontEnd, Target, warnings};

#[test]
fn the_list_states_the_limits_the_code_applies() {
    let t = brdf_export::table::markdown();
    assert!(
        t.contains(&format!(
            "with a warning above HDR-FLIP {FLIP_WARN} under any light set or mean-colour CIEDE2000 {DELTA_E_WARN}"
        )),
        "{t}"
    );
    assert!(
        t.contains(&format!(
            "refused above HDR-FLIP {FLIP_REFUSE} or CIEDE2000 {DELTA_E_REFUSE}"
        )),
        "{t}"
    );
    assert!(
        FLIP_WARN == 0.02 && FLIP_REFUSE == 0.1 && !t.contains("0.05 or"),
        "{t}"
    );
}

fn refused() -> ExportError {
    ExportError::LooksDifferent {
        model: "principled".into(),
        target: Target::Usd,
        via: "gltf".into(),
        flip: 0.034,
        delta_e: 0.5,
        front: FrontEnd::Cli,
    }
}

#[test]
fn a_refused_conversion_names_each_front_end_s_options() {
    let cli = refused().to_string();
    assert!(
        cli.contains("pass --force") && cli.contains("`brdf fit --model gltf ...`"),
        "{cli}"
    );
    let py = refused().for_front_end(FrontEnd::Python).to_string();
    assert!(
        py.contains("pass force=True") && py.contains("`brdf.fit(data, \"gltf\")`"),
        "{py}"
    );
    assert!(!py.contains("--"), "{py}");
    // Other errors pass unchanged.
    let other = ExportError::UnknownTarget("x".into());
    assert_eq!(other.clone().for_front_end(FrontEnd::Python), other);
}

#[test]
fn a_grey_fit_warns_for_every_target_and_an_rgb_fit_does_not() {
    let cfg = |channels| brdf_models::ModelConfig {
        channels,
        ..brdf_models::ModelConfig::default()
    };
    let grey = brdf_models::build("principled", &cfg(1)).unwrap();
    let rgb = brdf_models::build("principled", &cfg(3)).unwrap();
    for t in Target::ALL {
        let w = warnings(grey.as_ref(), t, FrontEnd::Cli);
        assert_eq!(w.len(), 1, "{t}");
        assert!(
            w[0].contains("one channel: its colour was never fitted"),
            "{}",
            w[0]
        );
        assert!(w[0].contains("`--channels rgb`"), "{}", w[0]);
        let w = warnings(grey.as_ref(), t, FrontEnd::Python);
        assert!(w[0].contains("`channels=\"rgb\"`"), "{}", w[0]);
        assert!(warnings(rgb.as_ref(), t, FrontEnd::Cli).is_empty(), "{t}");
    }
    // The exact export carries the same warning.
    let job_out = brdf_export::export_or_convert(
        grey.as_ref(),
        Target::Mitsuba,
        &brdf_export::ConvertOptions::default(),
    )
    .unwrap();
    assert_eq!(job_out.warnings.len(), 1);
}
