//! The candidates of a selection as a Markdown/CSV table.

use super::SelectRow;
use crate::table::{Cell, Table};

/// The candidates as a table, smallest first, the chosen one marked, with
/// a note saying why it was chosen. A column says which samples each row
/// was fitted to: the errors of screened-out rows are those of the coarse
/// subsample.
pub fn table(name: &str, rows: &[SelectRow], choice: usize, tolerance: f64) -> Table {
    let mut t = Table::new(
        &format!("Candidates for {name}"),
        &[
            "candidate",
            "stored numbers",
            "Ngan L2",
            "fitted on",
            "AIC",
            "BIC",
            "time (s)",
            "termination",
        ],
    );
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.sort_by(|a, b| {
        rows[*a]
            .stored_numbers
            .cmp(&rows[*b].stored_numbers)
            .then(rows[*a].error.total_cmp(&rows[*b].error))
    });
    let all = rows
        .iter()
        .filter(|r| !r.screened_out)
        .map(|r| r.samples)
        .max()
        .unwrap_or(0);
    for i in order {
        let r = &rows[i];
        let label = if i == choice {
            format!("**{}** (chosen)", r.label)
        } else {
            r.label.clone()
        };
        let fitted_on = if r.screened_out {
            format!("coarse subsample: {} samples (screened out)", r.samples)
        } else {
            format!("all {} samples", r.samples)
        };
        t.rows.push(vec![
            Cell::Text(label),
            Cell::Text(r.stored_numbers.to_string()),
            Cell::Num(r.error, 4),
            Cell::Text(fitted_on),
            criterion(r, r.aic),
            criterion(r, r.bic),
            Cell::Num(r.seconds, 3),
            Cell::Text(r.termination.clone()),
        ]);
    }
    if let Some(c) = rows.get(choice) {
        t.note = format!(
            "Chosen: {} ({} stored numbers, error {:.4e}): the fewest stored numbers within {} of the best error among the candidates fitted to all {all} samples.",
            c.label, c.stored_numbers, c.error, tolerance
        );
        let screened = rows.iter().filter(|r| r.screened_out).count();
        if screened > 0 {
            t.note.push_str(&format!(
                " {screened} candidates were screened out on the coarse subsample: their Ngan L2 is the coarse subsample's (not comparable with the others'), they have no AIC or BIC and cannot be chosen (`--exhaustive` fits them to all samples)."
            ));
        }
    }
    t
}

/// An information criterion's cell: empty for a screened-out row (the
/// criteria compare fits of the same samples).
fn criterion(r: &SelectRow, value: f64) -> Cell {
    if r.screened_out {
        Cell::Empty
    } else {
        Cell::Num(value, 5)
    }
}
