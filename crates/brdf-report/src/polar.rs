//! Polar plots of incidence-plane slices: for an incidence angle, the BRDF
//! (mean over channels) against the signed outgoing angle in the plane of
//! incidence, measured as points and fitted as a line, on a linear or a
//! logarithmic radius (drawn with plotters as inline SVG).
//!
//! Measured points: a dense data set evaluated along the plane, or, for
//! scattered data, the samples whose incidence lies within
//! [`THETA_TOL_DEG`] of the slice's and whose outgoing direction lies
//! within [`PHI_TOL_DEG`] of the plane.

use brdf_core::{Brdf, SampleSet};
use nalgebra::Vector3;
use plotters::prelude::*;

use crate::ReportError;

/// The incidence angles of the slices (degrees).
pub const INCIDENCE_DEG: [f64; 4] = [0.0, 30.0, 60.0, 75.0];
/// Scattered samples within this of the slice's incidence angle (degrees).
pub const THETA_TOL_DEG: f64 = 5.0;
/// Scattered samples within this of the plane of incidence (degrees).
pub const PHI_TOL_DEG: f64 = 15.0;
/// Outgoing angles drawn (degrees either side of the normal; grazing
/// values of tabulated data are extrapolations).
pub const MAX_THETA_O_DEG: f64 = 85.0;
/// Decades shown on the logarithmic radius.
pub const LOG_DECADES: f64 = 4.0;

/// One slice: `(signed outgoing angle in degrees, value)`; negative angles
/// lie on the specular side.
#[derive(Clone, Debug, Default)]
pub struct Slice {
    /// incidence angle (degrees)
    pub theta_i_deg: f64,
    /// measured points
    pub measured: Vec<(f64, f64)>,
    /// fitted line
    pub fitted: Vec<(f64, f64)>,
}

fn dir(theta_deg: f64) -> Vector3<f64> {
    let t = theta_deg.to_radians();
    Vector3::new(t.sin(), 0.0, t.cos())
}

fn mean_at(brdf: &dyn Brdf, l: &Vector3<f64>, v: &Vector3<f64>, buf: &mut [f64]) -> f64 {
    brdf.eval(l, v, buf);
    buf.iter().sum::<f64>() / buf.len().max(1) as f64
}

/// `brdf` along the plane of incidence at `theta_i_deg`, every `step_deg`.
pub fn along_plane(brdf: &dyn Brdf, theta_i_deg: f64, step_deg: f64) -> Vec<(f64, f64)> {
    let l = dir(theta_i_deg);
    let mut buf = vec![0.0; brdf.channels().max(1)];
    let n = (2.0 * MAX_THETA_O_DEG / step_deg).floor() as i64;
    (0..=n)
        .map(|k| -MAX_THETA_O_DEG + k as f64 * step_deg)
        .map(|t| (t, mean_at(brdf, &l, &dir(t), &mut buf)))
        .filter(|p| p.1.is_finite())
        .collect()
}

/// The scattered samples near the plane of incidence at `theta_i_deg`.
pub fn samples_near_plane(data: &SampleSet, theta_i_deg: f64) -> Vec<(f64, f64)> {
    let pairs = data.pairs();
    let nc = data.channels().max(1);
    let mut out = Vec::new();
    for j in 0..data.len() {
        let (l, v) = (pairs.l(j), pairs.v(j));
        let ti = l.z.clamp(-1.0, 1.0).acos().to_degrees();
        if (ti - theta_i_deg).abs() > THETA_TOL_DEG {
            continue;
        }
        let dphi = (v.y.atan2(v.x) - l.y.atan2(l.x))
            .to_degrees()
            .rem_euclid(360.0);
        let to = v.z.clamp(-1.0, 1.0).acos().to_degrees();
        if to > MAX_THETA_O_DEG {
            continue;
        }
        let t = if dphi.min(360.0 - dphi) <= PHI_TOL_DEG {
            to
        } else if (dphi - 180.0).abs() <= PHI_TOL_DEG {
            -to
        } else {
            continue;
        };
        let value = (0..nc).map(|c| data.channel(c)[j]).sum::<f64>() / nc as f64;
        if value.is_finite() {
            out.push((t, value));
        }
    }
    out
}

/// The four slices of the report.
pub fn slices(data: &SampleSet, dense: Option<&dyn Brdf>, fitted: &dyn Brdf) -> Vec<Slice> {
    INCIDENCE_DEG
        .iter()
        .map(|&ti| Slice {
            theta_i_deg: ti,
            measured: match dense {
                Some(d) => along_plane(d, ti, 4.0),
                None => samples_near_plane(data, ti),
            },
            fitted: along_plane(fitted, ti, 1.0),
        })
        .collect()
}

/// The radius of `v` on the plot: `v` (linear) or decades above
/// `peak / 10^LOG_DECADES` (log; 0 below).
fn radius(v: f64, peak: f64, log: bool) -> f64 {
    if !log {
        return v.max(0.0);
    }
    let floor = peak / 10f64.powf(LOG_DECADES);
    if v <= floor { 0.0 } else { (v / floor).log10() }
}

fn polar_xy(t_deg: f64, r: f64) -> (f64, f64) {
    let t = t_deg.to_radians();
    (r * t.sin(), r * t.cos())
}

/// The slice as an SVG polar plot (`log`: logarithmic radius).
pub fn svg(slice: &Slice, log: bool) -> Result<String, ReportError> {
    brdf_render::grid::font();
    let peak = slice
        .measured
        .iter()
        .chain(&slice.fitted)
        .map(|p| p.1)
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max)
        .max(1e-12);
    let rmax = radius(peak, peak, log) * 1.08;
    let mut out = String::new();
    draw(&mut out, slice, log, peak, rmax).map_err(|e| ReportError::Input {
        path: format!("polar plot at {} deg", slice.theta_i_deg),
        reason: e,
    })?;
    Ok(out)
}

fn draw(out: &mut String, s: &Slice, log: bool, peak: f64, rmax: f64) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<std::io::Error>| x.to_string();
    let root = SVGBackend::with_string(out, (320, 205)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let scale = if log { "log" } else { "linear" };
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("θi = {:.0}°, {scale}", s.theta_i_deg),
            ("sans-serif", 15),
        )
        .margin(6)
        .build_cartesian_2d(-rmax..rmax, 0.0..rmax)
        .map_err(e)?;
    grid(&mut chart, log, peak, rmax)?;
    let incident = polar_xy(s.theta_i_deg, rmax);
    chart
        .draw_series(LineSeries::new(
            vec![(0.0, 0.0), incident],
            RGBColor(150, 150, 150).stroke_width(1),
        ))
        .map_err(e)?;
    let pts = |v: &[(f64, f64)]| -> Vec<(f64, f64)> {
        v.iter()
            .map(|&(t, x)| polar_xy(t, radius(x, peak, log)))
            .collect()
    };
    let measured = RGBColor(31, 119, 180);
    chart
        .draw_series(
            pts(&s.measured)
                .into_iter()
                .map(|p| Circle::new(p, 2, measured.filled())),
        )
        .map_err(e)?
        .label("measured")
        .legend(move |(x, y)| Circle::new((x + 8, y), 3, measured.filled()));
    chart
        .draw_series(LineSeries::new(pts(&s.fitted), RED.stroke_width(2)))
        .map_err(e)?
        .label("fitted")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], RED.stroke_width(2)));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .label_font(("sans-serif", 11))
        .border_style(BLACK.mix(0.3))
        .background_style(WHITE.mix(0.8))
        .draw()
        .map_err(e)?;
    root.present().map_err(e)
}

type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Half circles at quarter radii (labelled with their value) and rays every
/// 30 degrees.
fn grid(chart: &mut Chart, log: bool, peak: f64, rmax: f64) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<std::io::Error>| x.to_string();
    let light = RGBColor(215, 215, 215);
    let top = rmax / 1.08;
    for k in 1..=4 {
        let r = top * k as f64 / 4.0;
        let arc: Vec<(f64, f64)> = (-90..=90).map(|t| polar_xy(t as f64, r)).collect();
        chart.draw_series(LineSeries::new(arc, light)).map_err(e)?;
        let value = if log {
            peak / 10f64.powf(LOG_DECADES - r)
        } else {
            r
        };
        chart
            .draw_series(std::iter::once(Text::new(
                brdf_core::format::number(value, 2),
                (r, 0.0),
                ("sans-serif", 9)
                    .into_font()
                    .color(&RGBColor(110, 110, 110)),
            )))
            .map_err(e)?;
    }
    for t in (-90..=90).step_by(30) {
        let ray = vec![(0.0, 0.0), polar_xy(t as f64, top)];
        chart.draw_series(LineSeries::new(ray, light)).map_err(e)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_radius_counts_decades_above_the_floor() {
        assert_eq!(radius(1.0, 1.0, true), LOG_DECADES);
        assert_eq!(radius(1e-9, 1.0, true), 0.0);
        assert_eq!(radius(0.5, 1.0, false), 0.5);
    }

    #[test]
    fn a_slice_draws_as_svg() {
        let s = Slice {
            theta_i_deg: 30.0,
            measured: vec![(-30.0, 2.0), (0.0, 0.3)],
            fitted: vec![(-60.0, 0.2), (-30.0, 1.9), (0.0, 0.3)],
        };
        for log in [false, true] {
            let svg = svg(&s, log).expect("draws");
            assert!(svg.starts_with("<svg") && svg.contains("fitted"), "{svg}");
        }
    }
}
