//! The `brdf fit` command on the real CUReT data when `BRDF_DATA` is set:
//! Kurt's ranking of the linear models on quarry tile.

mod common;

use std::process::Command;

#[test]
fn fit_command_on_curet_quarry_tile() {
    let Some(path) = common::data_file("curet/abrdf.dat") else {
        return;
    };
    let run = |model: &[&str]| -> f64 {
        let mut args = vec!["fit", "--json", "--data"];
        let spec = format!("{}#25", path.display());
        args.push(&spec);
        args.push("--model");
        args.extend_from_slice(model);
        let out = Command::new(env!("CARGO_BIN_EXE_brdf"))
            .args(&args)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["fits"][0]["data"], "curet#25 Quarry Tile");
        v["fits"][0]["ngan_l2"].as_f64().unwrap()
    };
    let lambert = run(&["lambert"]);
    let k8 = run(&["koenderink", "--order", "8"]);
    let p7 = run(&["polynomial", "--degree", "7"]);
    // Kurt's ranking on quarry tile (his RGB errors: Koenderink 0.0069 <
    // polynomial 0.0108); a diffuse-only model is far worse.
    assert!(k8 < p7 && p7 < lambert, "{k8} {p7} {lambert}");
    assert!(k8 > 0.0 && lambert < 0.1);
}
