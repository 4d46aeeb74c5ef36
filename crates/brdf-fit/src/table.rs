//! Report tables: CSV (machine-readable) and Markdown (readable). The
//! batch summary, the model selection and every table of the study
//! (`brdf-study`) are written with them, so they all look alike.

use std::fmt::Write as _;
use std::path::Path;

use brdf_core::format::number;

use crate::FitError;

/// A table cell.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    /// Text.
    Text(String),
    /// A number, printed with the given significant digits in Markdown and
    /// in full in CSV; a non-finite one (a failed fit's) as `-` and empty.
    Num(f64, usize),
    /// Nothing.
    Empty,
}

impl Cell {
    fn csv(&self) -> String {
        match self {
            Cell::Text(s) => s.clone(),
            Cell::Num(x, _) if !x.is_finite() => String::new(),
            Cell::Num(x, _) => format!("{x}"),
            Cell::Empty => String::new(),
        }
    }
    fn md(&self) -> String {
        match self {
            Cell::Text(s) => s.clone(),
            Cell::Num(x, _) if !x.is_finite() => "-".into(),
            Cell::Num(x, d) => number(*x, *d),
            Cell::Empty => String::new(),
        }
    }
}

/// A titled table with a note.
#[derive(Clone, Debug, Default)]
pub struct Table {
    /// Title (Markdown heading).
    pub title: String,
    /// Explanatory note under the title (what was run, how to read it).
    pub note: String,
    /// Column headers.
    pub columns: Vec<String>,
    /// Rows.
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    /// A new empty table.
    pub fn new(title: &str, columns: &[&str]) -> Self {
        Table {
            title: title.into(),
            columns: columns.iter().map(|s| s.to_string()).collect(),
            ..Default::default()
        }
    }

    /// Markdown text.
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "## {}\n", self.title);
        if !self.note.is_empty() {
            let _ = writeln!(s, "{}\n", self.note);
        }
        let _ = writeln!(s, "| {} |", self.columns.join(" | "));
        let _ = writeln!(s, "|{}", " --- |".repeat(self.columns.len()));
        for r in &self.rows {
            let cells: Vec<String> = r.iter().map(Cell::md).collect();
            let _ = writeln!(s, "| {} |", cells.join(" | "));
        }
        s
    }

    /// Write `<stem>.csv` and `<stem>.md` into `dir`.
    pub fn write(&self, dir: &Path, stem: &str) -> Result<(), FitError> {
        let csv_path = dir.join(format!("{stem}.csv"));
        let io = |p: &Path, e: std::io::Error| FitError::Io {
            path: p.display().to_string(),
            source: e,
        };
        let mut w = csv::Writer::from_path(&csv_path)
            .map_err(|e| io(&csv_path, std::io::Error::other(e.to_string())))?;
        w.write_record(&self.columns)
            .map_err(|e| io(&csv_path, std::io::Error::other(e.to_string())))?;
        for r in &self.rows {
            w.write_record(r.iter().map(Cell::csv))
                .map_err(|e| io(&csv_path, std::io::Error::other(e.to_string())))?;
        }
        w.flush().map_err(|e| io(&csv_path, e))?;
        let md_path = dir.join(format!("{stem}.md"));
        std::fs::write(&md_path, self.markdown()).map_err(|e| io(&md_path, e))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_numbers_are_never_printed() {
        let mut t = Table::new("t", &["a", "b", "c"]);
        t.rows.push(vec![
            Cell::Num(f64::NAN, 3),
            Cell::Num(f64::INFINITY, 3),
            Cell::Num(0.25, 2),
        ]);
        let md = t.markdown();
        assert!(!md.contains("NaN") && !md.contains("inf"), "{md}");
        assert!(md.contains("| - | - | 0.25 |"), "{md}");
        assert_eq!(t.rows[0][0].csv(), "");
    }

    #[test]
    fn markdown_layout() {
        let mut t = Table::new("T", &["a", "b"]);
        t.rows.push(vec![Cell::Text("x".into()), Cell::Num(0.5, 2)]);
        assert_eq!(
            t.markdown(),
            "## T\n\n| a | b |\n| --- | --- |\n| x | 0.50 |\n"
        );
    }
}
