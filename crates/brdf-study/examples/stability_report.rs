//! Write `stability.md` / `stability.csv` (and, with `BRDF_DATA` set,
//! `stability_nist.*`) into the folder given (default `results`), until
//! `brdf reproduce --only stability` runs the same function:
//! `cargo run --release -p brdf-study --example stability_report -- results`.

fn main() -> std::process::ExitCode {
    let out = std::env::args().nth(1).unwrap_or_else(|| "results".into());
    match brdf_study::stability::write_stability_report(std::path::Path::new(&out)) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
