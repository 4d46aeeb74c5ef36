//! The README's times are the ones its scripts measured: the quick start's
//! those `benches/readme/quickstart.sh` wrote into `results/quickstart.md`,
//! the set-up commands' those `benches/readme/setup.sh` wrote into
//! `results/setup.md`, each for the commands the README holds now: a
//! command edited without rerunning the script, or a time edited by hand,
//! fails here.

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

/// The commands of the set-up section's plain code blocks.
fn set_up_commands(readme: &str) -> Vec<String> {
    let start = readme.find("## Set-up").expect("a set-up section");
    let section = &readme[start + 1..];
    let section = &section[..section.find("\n## ").unwrap_or(section.len())];
    section
        .split("```")
        .skip(1)
        .step_by(2)
        .map(|block| block.trim().to_string())
        .collect()
}

/// Check that the README's table between the `marker` comments is the
/// table of `results` and times exactly `commands`, each a number.
fn check_timed_table(readme: &str, marker: &str, results: &str, commands: &[String]) {
    let begin = format!("<!-- {marker}: benches/readme/");
    let end = format!("<!-- /{marker} -->");
    let inside = readme
        .split(&begin)
        .nth(1)
        .and_then(|r| r.split(&end).next())
        .unwrap_or_else(|| panic!("the README's {marker} markers"));
    let script = format!(
        "benches/readme/{}",
        inside.split(" -->").next().unwrap_or("")
    );
    let results_text = read(results);
    assert_eq!(
        table_rows(inside),
        table_rows(&results_text),
        "README's times differ from {results}: rerun {script}"
    );
    let timed: Vec<String> = table_rows(&results_text)
        .iter()
        .skip(2)
        .map(|row| {
            let cell = row.split('|').nth(1).expect("a command cell").trim();
            cell.trim_matches('`').to_string()
        })
        .collect();
    assert_eq!(
        timed, commands,
        "the README's commands changed: rerun {script}"
    );
    for row in table_rows(&results_text).iter().skip(2) {
        let time: f64 = row
            .split('|')
            .nth(2)
            .and_then(|c| c.trim().parse().ok())
            .unwrap_or_else(|| panic!("no time in {row}"));
        assert!(time.is_finite() && time >= 0.0, "{row}");
    }
}

#[test]
fn quick_start_times_are_the_script_s_for_the_commands_shown() {
    let readme = read("README.md");
    let commands = quick_start_commands(&readme);
    check_timed_table(
        &readme,
        "quickstart-times",
        "results/quickstart.md",
        &commands,
    );
}

#[test]
fn set_up_times_are_the_script_s_for_the_two_commands() {
    let readme = read("README.md");
    let commands = set_up_commands(&readme);
    assert_eq!(commands.len(), 2, "the set-up section holds two commands");
    check_timed_table(&readme, "setup-times", "results/setup.md", &commands);
}

/// The rows between `<!-- renderers-figure: ... -->` and its end marker in
/// `text`.
fn figure_rows(text: &str) -> Vec<&str> {
    let inside = text
        .split("<!-- renderers-figure: results/renderers/renderers.md -->")
        .nth(1)
        .and_then(|r| r.split("<!-- /renderers-figure -->").next())
        .expect("the renderers-figure markers");
    table_rows(inside)
}

/// The renderer figure in the README and in docs/export.md is the table
/// `results/renderers/make.sh` wrote (its image paths relative to each
/// page), so its figures are the ones the renderers measured.
#[test]
fn the_renderer_figure_is_the_one_make_sh_wrote() {
    let written = read("results/renderers/renderers.md");
    let rows = table_rows(&written);
    assert!(rows.len() >= 3, "{written}");
    assert_eq!(figure_rows(&read("README.md")), rows);
    let docs: Vec<String> = rows
        .iter()
        .map(|r| r.replace("](results/", "](../results/"))
        .collect();
    assert_eq!(figure_rows(&read("docs/export.md")), docs);
}
