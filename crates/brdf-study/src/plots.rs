//! SVG plots of the study's figures (feature `plots`, plotters' SVG
//! backend): curves (error against degree or against material) and the
//! error-against-time scatter with its Pareto front marked.

use std::path::Path;

use plotters::prelude::*;

use crate::StudyError;

/// One named series of points.
#[derive(Clone, Debug)]
pub struct Series {
    /// legend name
    pub name: String,
    /// `(x, y)` points
    pub points: Vec<(f64, f64)>,
}

fn err(path: &Path, e: impl std::fmt::Display) -> StudyError {
    StudyError::Io {
        path: path.display().to_string(),
        source: std::io::Error::other(e.to_string()),
    }
}

fn range(series: &[Series], f: impl Fn(&(f64, f64)) -> f64, log: bool) -> (f64, f64) {
    let vals = series
        .iter()
        .flat_map(|s| s.points.iter().map(&f))
        .filter(|v| v.is_finite() && (!log || *v > 0.0));
    let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if !lo.is_finite() {
        return (if log { 1e-3 } else { 0.0 }, 1.0);
    }
    if log {
        (lo / 1.5, hi * 1.5)
    } else {
        let pad = ((hi - lo) * 0.05).max(1e-12);
        (lo - pad, hi + pad)
    }
}

/// Draw lines (`lines = true`) or points for every series; `log_y` puts the
/// y axis on a log scale (`log_x` likewise).
pub fn plot_series(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    lines: bool,
    log_x: bool,
    log_y: bool,
    pareto: Option<&[(f64, f64)]>,
) -> Result<(), StudyError> {
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(path, e))?;
    let (x0, x1) = range(series, |p| p.0, log_x);
    let (y0, y1) = range(series, |p| p.1, log_y);
    let mut builder = ChartBuilder::on(&root);
    builder
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70);
    macro_rules! draw {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(x_label)
                .y_desc(y_label)
                .draw()
                .map_err(|e| err(path, e))?;
            for (i, s) in series.iter().enumerate() {
                let color = Palette99::pick(i).to_rgba();
                let pts: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .copied()
                    .filter(|(x, y)| {
                        x.is_finite()
                            && y.is_finite()
                            && (!log_x || *x > 0.0)
                            && (!log_y || *y > 0.0)
                    })
                    .collect();
                if lines {
                    chart
                        .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                        .map_err(|e| err(path, e))?
                        .label(s.name.clone())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
                    chart
                        .draw_series(pts.iter().map(|p| Circle::new(*p, 3, color.filled())))
                        .map_err(|e| err(path, e))?;
                } else {
                    chart
                        .draw_series(pts.iter().map(|p| Circle::new(*p, 4, color.filled())))
                        .map_err(|e| err(path, e))?
                        .label(s.name.clone())
                        .legend(move |(x, y)| Circle::new((x + 9, y), 4, color.filled()));
                }
            }
            if let Some(front) = pareto {
                let pts: Vec<(f64, f64)> = front.to_vec();
                chart
                    .draw_series(LineSeries::new(pts, BLACK.stroke_width(1)))
                    .map_err(|e| err(path, e))?
                    .label("Pareto front")
                    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK));
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()
                .map_err(|e| err(path, e))?;
        }};
    }
    match (log_x, log_y) {
        (false, false) => draw!(
            builder
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(|e| err(path, e))?
        ),
        (false, true) => draw!(
            builder
                .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
                .map_err(|e| err(path, e))?
        ),
        (true, false) => draw!(
            builder
                .build_cartesian_2d((x0..x1).log_scale(), y0..y1)
                .map_err(|e| err(path, e))?
        ),
        (true, true) => draw!(
            builder
                .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
                .map_err(|e| err(path, e))?
        ),
    }
    root.present().map_err(|e| err(path, e))?;
    Ok(())
}

/// The Pareto front of `(time, error)` points (minimise both), sorted by time.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut p: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for q in p {
        if front.last().is_none_or(|l| q.1 < l.1) {
            front.push(q);
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pareto_front_keeps_only_undominated_points() {
        let f = pareto_front(&[(1.0, 5.0), (2.0, 3.0), (3.0, 4.0), (0.5, 9.0), (4.0, 1.0)]);
        assert_eq!(f, vec![(0.5, 9.0), (1.0, 5.0), (2.0, 3.0), (4.0, 1.0)]);
    }

    #[test]
    fn writes_an_svg() {
        let dir = std::env::temp_dir().join(format!("brdf-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("t.svg");
        let s = vec![Series {
            name: "a".into(),
            points: vec![(1.0, 0.1), (2.0, 0.01), (3.0, 0.005)],
        }];
        plot_series(&p, "t", "x", "y", &s, true, false, true, None).unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        assert!(text.contains("<svg") && text.contains("polyline"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
