//! `brdf reproduce` on the built-in synthetic data writes the expected files,
//! says it used synthetic data, writes into its own `synthetic/` folder
//! (never over the measured results), and gives the same numbers when rerun.

use std::process::Command;

#[test]
fn reproduce_on_synthetic_data_writes_tables_and_is_deterministic() {
    let top = std::env::temp_dir().join(format!("brdf-smoke-{}", std::process::id()));
    let dir = top.join("synthetic");
    let run = || {
        let out = Command::new(env!("CARGO_BIN_EXE_brdf"))
            .args(["reproduce", "--out"])
            .arg(&top)
            .env_remove("BRDF_DATA")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(String::from_utf8_lossy(&out.stderr).contains("synthetic"));
        std::fs::read_to_string(dir.join("kurt_9_1.csv")).unwrap()
    };
    let first = run();
    assert_eq!(first.lines().count(), 13, "{first}");
    assert!(first.starts_with("degree p,"));
    let md = std::fs::read_to_string(dir.join("kurt_9_1.md")).unwrap();
    assert!(md.contains("BUILT-IN SYNTHETIC DATA"));
    let fig = std::fs::read_to_string(dir.join("kurt_9_5.csv")).unwrap();
    assert_eq!(fig.lines().count(), 1 + 5);
    assert!(dir.join("kurt_9_5.svg").exists() && dir.join("kurt_9_5.png").exists());
    let readme = std::fs::read_to_string(dir.join("README.md")).unwrap();
    assert!(
        readme.contains("BUILT-IN SYNTHETIC DATA")
            && readme.contains("`kurt_9_5.{csv,md,svg,png}`")
    );
    assert_eq!(run(), first);
    assert!(
        !top.join("kurt_9_1.csv").exists(),
        "synthetic results outside synthetic/"
    );
    std::fs::remove_dir_all(&top).unwrap();
}
