//! The README's quick-start times are the ones `benches/readme/quickstart.sh`
//! measured and wrote into `results/quickstart.md`, for the commands the
//! quick-start block holds now: a command edited without rerunning the
//! script, or a time edited by hand, fails here.

use std::path::PathBuf;

fn read(rel: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(rel);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The table rows (lines starting with `|`) of `text`.
fn table_rows(text: &str) -> Vec<&str> {
    text.lines().filter(|l| l.starts_with('|')).collect()
}

/// The `brdf` commands of the README's quick-start block, comments cut.
fn quick_start_commands(readme: &str) -> Vec<String> {
    let start = readme
        .find("## Quick start")
        .expect("a quick-start section");
    let block = &readme[start..];
    let open = block.find("```bash").expect("a bash block") + "```bash".len();
    let body = &block[open..];
    let close = body.find("```").expect("the block closes");
    body[..close]
        .lines()
        .filter(|l| l.starts_with("brdf "))
        .map(|l| l.split("  #").next().unwrap_or(l).trim_end().to_string())
        .collect()
}

#[test]
fn quick_start_times_are_the_script_s_for_the_commands_shown() {
    let readme = read("README.md");
    let begin = "<!-- quickstart-times: benches/readme/quickstart.sh -->";
    let end = "<!-- /quickstart-times -->";
    let inside = readme
        .split(begin)
        .nth(1)
        .and_then(|r| r.split(end).next())
        .expect("the README's quickstart-times markers");
    let results = read("results/quickstart.md");
    assert_eq!(
        table_rows(inside),
        table_rows(&results),
        "README's times differ from results/quickstart.md: rerun benches/readme/quickstart.sh"
    );
    let timed: Vec<String> = table_rows(&results)
        .iter()
        .skip(2)
        .map(|row| {
            let cell = row.split('|').nth(1).expect("a command cell").trim();
            cell.trim_matches('`').to_string()
        })
        .collect();
    assert_eq!(
        timed,
        quick_start_commands(&readme),
        "the quick-start block changed: rerun benches/readme/quickstart.sh"
    );
    for row in table_rows(&results).iter().skip(2) {
        let secs: f64 = row
            .split('|')
            .nth(2)
            .and_then(|c| c.trim().parse().ok())
            .unwrap_or_else(|| panic!("no time in {row}"));
        assert!(secs.is_finite() && secs >= 0.0, "{row}");
    }
}
