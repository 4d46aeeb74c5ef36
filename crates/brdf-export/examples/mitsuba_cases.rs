//! Writes the models whose Mitsuba export `tests/reference/mitsuba_check.py`
//! evaluates: `cargo run -p brdf-export --example mitsuba_cases >
//! crates/brdf-export/tests/reference/mitsuba_cases.json`.

fn main() {
    let cases = brdf_export_cases::cases();
    let out: Vec<serde_json::Value> = cases
        .iter()
        .map(|(name, channels, lobes, p)| {
            let m = brdf_export_cases::build(name, *channels, *lobes, p);
            let xml = brdf_export::export(m.as_ref(), brdf_export::Target::Mitsuba)
                .unwrap_or_else(|e| panic!("{e}"));
            serde_json::json!({"model": name, "channels": channels, "lobes": lobes, "params": p, "xml": xml})
        })
        .collect();
    println!("{}", serde_json::to_string_pretty(&out).unwrap_or_default());
}

#[path = "../tests/export/cases.rs"]
mod brdf_export_cases;
