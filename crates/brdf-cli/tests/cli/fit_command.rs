//! The `brdf fit` command on the real CUReT data when `BRDF_DATA` is set:
//! Kurt's ranking of the linear models on quarry tile.

use crate::common;

/// The first fit of `brdf fit --json ARGS`.
fn fit_json(args: &[&str]) -> serde_json::Value {
    let mut all = vec!["fit", "--json", "--quiet"];
    all.extend_from_slice(args);
    let (ok, stdout, stderr) = common::brdf(&all);
    assert!(ok, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    v["fits"][0].clone()
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn fit_command_on_curet_quarry_tile() {
    let path = common::data_file("curet/abrdf.dat");
    let run = |model: &[&str]| -> f64 {
        let spec = format!("{}#25", path.display());
        let mut args = vec!["--data", &spec, "--model"];
        args.extend_from_slice(model);
        let fit = fit_json(&args);
        assert_eq!(fit["data"], "curet#25 Quarry Tile");
        fit["ngan_l2"].as_f64().unwrap()
    };
    let lambert = run(&["lambert"]);
    let k8 = run(&["koenderink", "--order", "8"]);
    let p7 = run(&["polynomial", "--degree", "7"]);
    // Kurt's ranking on quarry tile (his RGB errors: Koenderink 0.0069 <
    // polynomial 0.0108); a diffuse-only model is far worse.
    assert!(k8 < p7 && p7 < lambert, "{k8} {p7} {lambert}");
    assert!(k8 > 0.0 && lambert < 0.1);
}

/// The robust fit's reweighting cap: with MATLAB's 50 the degree-7
/// polynomial on paper_white stops short in every channel; the default
/// cap lets each converge (measured: 64, 60 and 61 reweightings), and the
/// reported iterations are their sum.
#[test]
#[ignore = "needs BRDF_DATA"]
fn the_irls_cap_decides_whether_the_polynomial_converges() {
    let path = common::data_file("rgl/paper_white_rgb.bsdf");
    let run = |extra: &[&str]| -> serde_json::Value {
        let data = path.display().to_string();
        let mut args = vec!["--data", &data, "--model", "polynomial"];
        args.extend_from_slice(extra);
        fit_json(&args)
    };
    let matlab = run(&["--irls-max-iterations", "50"]);
    assert_eq!(
        matlab["termination"],
        "IRLS NOT converged: iteration cap reached"
    );
    assert_eq!(matlab["iterations"], 150);
    let default = run(&[]);
    let t = default["termination"].as_str().unwrap();
    assert!(t.starts_with("IRLS converged"), "{t}");
    let counts: Vec<u64> = default["solver"]
        .as_str()
        .unwrap()
        .rsplit_once("), ")
        .unwrap()
        .1
        .split(" iterations")
        .next()
        .unwrap()
        .split(" / ")
        .map(|k| k.parse().unwrap())
        .collect();
    assert!(counts.iter().all(|&k| k > 50), "{counts:?}");
    assert_eq!(default["iterations"], counts.iter().sum::<u64>());
}

/// A robust fit whose reweighting cycles (the degree-3 polynomial on
/// CUReT's quarry tile, which never converges) stops when a weighted
/// solution recurs, well before the cap, and says so; at MATLAB's cap of
/// 50 it has not recurred yet and stops at the cap.
#[test]
#[ignore = "needs BRDF_DATA"]
fn a_cycling_robust_fit_stops_and_says_so() {
    let path = common::data_file("curet/abrdf.dat");
    let spec = format!("{}#25", path.display());
    let args = ["--data", &spec, "--model", "polynomial", "--degree", "3"];
    let fit = fit_json(&args);
    assert_eq!(
        fit["termination"],
        "IRLS NOT converged: the reweighting cycles (a weighted solution recurred)"
    );
    let k = fit["iterations"].as_u64().unwrap();
    assert!(k > 50 && k < 500, "{k}");
    let capped = fit_json(&[&args[..], &["--irls-max-iterations", "50"]].concat());
    assert_eq!(
        capped["termination"],
        "IRLS NOT converged: iteration cap reached"
    );
}
