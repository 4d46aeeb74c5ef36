//! `brdf select --data PATH [--tolerance REL] [--json]`: fit the candidate
//! models and choose the smallest one within the tolerance of the best.

use crate::StudyError;
use crate::pipeline::FitOptions;
use crate::report::{Cell, Table};

/// Arguments of `brdf select`.
#[derive(Debug, clap::Args)]
pub struct SelectArgs {
    /// Data set: `PATH` or `PATH#SAMPLE`.
    #[arg(long)]
    pub data: String,
    /// Accept errors up to (1 + REL) times the best.
    #[arg(long, default_value_t = 0.1)]
    pub tolerance: f64,
    /// Drop samples with theta_i or theta_o above this angle (degrees).
    #[arg(long, default_value_t = 80.0)]
    pub limit: f64,
    /// Fit the mean of the channels (grey) instead of every channel.
    #[arg(long)]
    pub grey: bool,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
}

/// Run `brdf select`.
pub fn run(args: &SelectArgs) -> Result<(), StudyError> {
    if !(args.limit > 0.0 && args.limit <= 90.0) {
        return Err(StudyError::Usage(format!(
            "--limit {} must be in (0, 90] degrees",
            args.limit
        )));
    }
    let data = crate::data::load(&args.data)?;
    let (data, _) = data.filter_invalid(false);
    let (data, _) = data.filter_angle_limit(args.limit.to_radians());
    let data = if args.grey { data.mean_channel() } else { data };
    let (rows, choice) = crate::select::select(&data, args.tolerance, &FitOptions::default())?;
    if args.json {
        let v = serde_json::json!({ "data": data.name, "tolerance": args.tolerance, "choice": rows[choice], "candidates": rows });
        say!("{}", serde_json::to_string_pretty(&v)?)?;
        return Ok(());
    }
    let mut t = Table::new(
        &format!("Candidates for {}", data.name),
        &[
            "candidate",
            "stored numbers",
            "Ngan L2",
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
    for i in order {
        let r = &rows[i];
        t.rows.push(vec![
            Cell::Text(if i == choice {
                format!("**{}** (chosen)", r.label)
            } else {
                r.label.clone()
            }),
            Cell::Text(r.stored_numbers.to_string()),
            Cell::Num(r.error, 4),
            Cell::Num(r.aic, 5),
            Cell::Num(r.bic, 5),
            Cell::Num(r.seconds, 3),
            Cell::Text(r.termination.clone()),
        ]);
    }
    t.note = format!(
        "Chosen: {} ({} stored numbers, error {:.4e}): the fewest stored numbers within {} of the best error.",
        rows[choice].label, rows[choice].stored_numbers, rows[choice].error, args.tolerance
    );
    say_raw!("{}", t.markdown())?;
    Ok(())
}
