//! Plots of the study's figures, each written as SVG and PNG (plotters; the
//! PNG's text in the font bundled with the binary, so a machine without
//! system fonts draws it): markers and/or lines per series in
//! distinguishable colours and shapes, the legend beside the plot (never
//! over the data), log axes, integer axes for ranks and degrees, and a
//! Pareto front drawn as a step line.

use std::path::Path;

use plotters::coord::Shift;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;

use crate::RenderError;
use crate::grid::{font, write_rgb_png};

/// One named series of points.
#[derive(Clone, Debug)]
pub struct Series {
    /// legend name (`None`: not in the legend)
    pub name: Option<String>,
    /// `(x, y)` points
    pub points: Vec<(f64, f64)>,
    /// colour and marker index
    pub style: usize,
    /// join the points by a line
    pub line: bool,
    /// marker radius in pixels (0: none)
    pub marker: u32,
    /// opacity
    pub alpha: f64,
}

impl Series {
    /// Markers only, in the legend.
    pub fn points(name: &str, style: usize, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: Some(name.into()),
            points,
            style,
            line: false,
            marker: 4,
            alpha: 1.0,
        }
    }
}

/// A plot.
#[derive(Clone, Debug, Default)]
pub struct Plot {
    /// title
    pub title: String,
    /// x axis label
    pub x_label: String,
    /// y axis label
    pub y_label: String,
    /// series
    pub series: Vec<Series>,
    /// log x axis
    pub log_x: bool,
    /// log y axis
    pub log_y: bool,
    /// x tick labels as integers (ranks, degrees)
    pub integer_x: bool,
    /// Pareto front, drawn as a step line through its points
    pub pareto: Option<Vec<(f64, f64)>>,
}

/// Tableau-like qualitative colours: neighbours differ in hue and lightness.
const COLOURS: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

fn colour(style: usize, alpha: f64) -> RGBAColor {
    let (r, g, b) = COLOURS[style % COLOURS.len()];
    RGBColor(r, g, b).mix(alpha)
}

fn err(path: &Path, e: impl std::fmt::Display) -> RenderError {
    RenderError::Io {
        path: path.display().to_string(),
        source: std::io::Error::other(e.to_string()),
    }
}

fn range(plot: &Plot, f: impl Fn(&(f64, f64)) -> f64, log: bool) -> (f64, f64) {
    let vals = plot
        .series
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
        (lo / 1.3, hi * 1.3)
    } else {
        let pad = ((hi - lo) * 0.05).max(0.5 * f64::EPSILON.sqrt() * hi.abs().max(1.0));
        (lo - pad, hi + pad)
    }
}

/// A tick label: on a log axis only the 1-2-5 values are labelled (the
/// others are drawn unlabelled, so labels never crowd).
fn tick(v: f64, log: bool) -> String {
    if log && v > 0.0 {
        let m = v / 10f64.powf(v.log10().floor());
        if ![1.0, 2.0, 5.0].iter().any(|k| (m - k).abs() < 1e-6) {
            return String::new();
        }
    }
    brdf_core::format::number(v, 2)
}

/// A marker of shape `style / 10` (circle, triangle, square, cross).
fn marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (x, y): (i32, i32),
    style: usize,
    size: u32,
    c: RGBAColor,
) -> Result<(), String> {
    let s = size as i32;
    let r = match (style / 4) % 4 {
        0 => area.draw(&Circle::new((x, y), s, c.filled())),
        1 => area.draw(&TriangleMarker::new((x, y), s + 1, c.filled())),
        2 => area.draw(&Rectangle::new(
            [(x - s, y - s), (x + s, y + s)],
            c.filled(),
        )),
        _ => area.draw(&Cross::new((x, y), s, c.stroke_width(2))),
    };
    r.map_err(|e| e.to_string())
}

/// Shape index of a series: colours cycle fastest, shapes change every 4.
fn shape(style: usize) -> usize {
    style % 4 * 4 + style / 4
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, plot: &Plot) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let (w, _) = root.dim_in_pixel();
    let (chart_area, legend_area) = root.split_horizontally(w as i32 - 230);
    let (x0, x1) = range(plot, |p| p.0, plot.log_x);
    let (y0, y1) = range(plot, |p| p.1, plot.log_y);
    let mut builder = ChartBuilder::on(&chart_area);
    builder
        .caption(&plot.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75);
    // The coordinate type differs with each combination of log axes, so
    // each gets its own instance of the generic chart drawing.
    let corner = (x1, y0);
    match (plot.log_x, plot.log_y) {
        (false, false) => draw_chart(
            builder.build_cartesian_2d(x0..x1, y0..y1).map_err(e)?,
            plot,
            corner,
        )?,
        (false, true) => draw_chart(
            builder
                .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
                .map_err(e)?,
            plot,
            corner,
        )?,
        (true, false) => draw_chart(
            builder
                .build_cartesian_2d((x0..x1).log_scale(), y0..y1)
                .map_err(e)?,
            plot,
            corner,
        )?,
        (true, true) => draw_chart(
            builder
                .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
                .map_err(e)?,
            plot,
            corner,
        )?,
    }
    draw_legend(&legend_area, plot)?;
    root.present().map_err(e)?;
    Ok(())
}

/// The axes, the Pareto front and the series in the chart; `corner` is
/// `(x_max, y_min)` of the axes, where the front's last step ends.
fn draw_chart<DB, X, Y>(
    mut chart: ChartContext<'_, DB, Cartesian2d<X, Y>>,
    plot: &Plot,
    corner: (f64, f64),
) -> Result<(), String>
where
    DB: DrawingBackend,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let xfmt = |x: &f64| x_tick(*x, plot);
    let yfmt = |y: &f64| tick(*y, plot.log_y);
    chart
        .configure_mesh()
        .x_desc(plot.x_label.as_str())
        .y_desc(plot.y_label.as_str())
        .x_label_formatter(&xfmt)
        .y_label_formatter(&yfmt)
        .light_line_style(WHITE)
        .draw()
        .map_err(e)?;
    if let Some(front) = &plot.pareto {
        draw_pareto(&mut chart, plot, front, corner)?;
    }
    for s in &plot.series {
        draw_series(&mut chart, plot, s)?;
    }
    Ok(())
}

/// An x tick label: with [`Plot::integer_x`] only whole numbers are
/// labelled (ranks, degrees), else as [`tick`].
fn x_tick(x: f64, plot: &Plot) -> String {
    if plot.integer_x {
        if (x - x.round()).abs() < 1e-9 {
            format!("{:.0}", x)
        } else {
            String::new()
        }
    } else {
        tick(x, plot.log_x)
    }
}

/// Whether a point can be drawn on the plot's axes (finite, and positive
/// on a log axis): the others are left out rather than failing the plot.
fn drawable(plot: &Plot, (x, y): &(f64, f64)) -> bool {
    x.is_finite() && y.is_finite() && (!plot.log_x || *x > 0.0) && (!plot.log_y || *y > 0.0)
}

/// The Pareto front as a step line: the best error reachable within a time
/// budget, held to the right edge (`corner.0`) after the last point.
fn draw_pareto<DB, CT>(
    chart: &mut ChartContext<'_, DB, CT>,
    plot: &Plot,
    front: &[(f64, f64)],
    (x1, y0): (f64, f64),
) -> Result<(), String>
where
    DB: DrawingBackend,
    CT: CoordTranslate<From = (f64, f64)>,
{
    let mut steps = Vec::new();
    for (k, p) in front.iter().enumerate() {
        if k > 0 {
            steps.push((p.0, front[k - 1].1));
        }
        steps.push(*p);
    }
    steps.push((x1, front.last().map_or(y0, |p| p.1)));
    let steps: Vec<(f64, f64)> = steps.into_iter().filter(|p| drawable(plot, p)).collect();
    chart
        .draw_series(LineSeries::new(steps, BLACK.stroke_width(2)))
        .map_err(|x| x.to_string())?;
    Ok(())
}

/// One series: its line, then its markers on top, in the shape of
/// [`shape`] (the same as in the legend).
fn draw_series<DB, CT>(
    chart: &mut ChartContext<'_, DB, CT>,
    plot: &Plot,
    s: &Series,
) -> Result<(), String>
where
    DB: DrawingBackend,
    CT: CoordTranslate<From = (f64, f64)>,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let c = colour(s.style, s.alpha);
    let pts: Vec<(f64, f64)> = s
        .points
        .iter()
        .copied()
        .filter(|p| drawable(plot, p))
        .collect();
    if s.line {
        chart
            .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
            .map_err(e)?;
    }
    if s.marker == 0 {
        return Ok(());
    }
    let z = s.marker as i32;
    let at = |p: &(f64, f64)| EmptyElement::at(*p);
    match (shape(s.style) / 4) % 4 {
        0 => chart
            .draw_series(
                pts.iter()
                    .map(|p| at(p) + Circle::new((0, 0), z, c.filled())),
            )
            .map(|_| ()),
        1 => chart
            .draw_series(
                pts.iter()
                    .map(|p| at(p) + TriangleMarker::new((0, 0), z + 1, c.filled())),
            )
            .map(|_| ()),
        2 => chart
            .draw_series(
                pts.iter()
                    .map(|p| at(p) + Rectangle::new([(-z, -z), (z, z)], c.filled())),
            )
            .map(|_| ()),
        _ => chart
            .draw_series(
                pts.iter()
                    .map(|p| at(p) + Cross::new((0, 0), z, c.stroke_width(2))),
            )
            .map(|_| ()),
    }
    .map_err(e)
}

/// The legend, beside the plot (never over the data): a line and a marker
/// per named series as drawn in the chart, then the Pareto front's line.
fn draw_legend<DB: DrawingBackend>(
    legend_area: &DrawingArea<DB, Shift>,
    plot: &Plot,
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let mut y = 50;
    let text = |s: &str, x: i32, y: i32| {
        legend_area
            .draw(&Text::new(
                s.to_string(),
                (x, y),
                ("sans-serif", 13).into_font().color(&BLACK),
            ))
            .map_err(|x| x.to_string())
    };
    for s in plot.series.iter().filter(|s| s.name.is_some()) {
        let c = colour(s.style, 1.0);
        if s.line {
            legend_area
                .draw(&PathElement::new(vec![(4, y), (28, y)], c.stroke_width(2)))
                .map_err(e)?;
        }
        marker(legend_area, (16, y), shape(s.style), s.marker.max(3), c)?;
        text(s.name.as_deref().unwrap_or(""), 36, y - 7)?;
        y += 22;
    }
    if plot.pareto.is_some() {
        legend_area
            .draw(&PathElement::new(
                vec![(4, y), (28, y)],
                BLACK.stroke_width(2),
            ))
            .map_err(e)?;
        text("Pareto front", 36, y - 7)?;
    }
    Ok(())
}

/// Write `stem.svg` and `stem.png` into `dir`.
pub fn write(plot: &Plot, dir: &Path, stem: &str) -> Result<(), RenderError> {
    font();
    let (w, h) = (1000u32, 600u32);
    let svg = dir.join(format!("{stem}.svg"));
    draw(SVGBackend::new(&svg, (w, h)).into_drawing_area(), plot).map_err(|x| err(&svg, x))?;
    let png = dir.join(format!("{stem}.png"));
    let mut buf = vec![255u8; (w * h * 3) as usize];
    draw(
        BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area(),
        plot,
    )
    .map_err(|x| err(&png, x))?;
    write_rgb_png(&png, w as usize, h as usize, &buf)
}

/// The plot as an SVG document in memory (for inline SVG in HTML).
pub fn svg(plot: &Plot, (w, h): (u32, u32)) -> Result<String, RenderError> {
    font();
    let mut out = String::new();
    draw(
        SVGBackend::with_string(&mut out, (w, h)).into_drawing_area(),
        plot,
    )
    .map_err(|x| err(Path::new("in-memory SVG"), x))?;
    Ok(out)
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
    fn writes_an_svg_and_a_png_with_the_legend_outside_the_data() {
        let dir = std::env::temp_dir().join(format!("brdf-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut a = Series::points("alpha", 0, vec![(1.0, 0.1), (2.0, 0.01), (3.0, 0.005)]);
        a.line = true;
        let plot = Plot {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![a],
            log_y: true,
            integer_x: true,
            pareto: Some(vec![(1.0, 0.1), (3.0, 0.005)]),
            ..Plot::default()
        };
        write(&plot, &dir, "t").unwrap();
        let text = std::fs::read_to_string(dir.join("t.svg")).unwrap();
        assert!(text.contains("<svg") && text.contains("alpha") && text.contains("Pareto front"));
        let dec = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(dir.join("t.png")).unwrap(),
        ));
        let mut r = dec.read_info().unwrap();
        let mut px = vec![0; r.output_buffer_size().unwrap()];
        let info = r.next_frame(&mut px).unwrap();
        assert_eq!((info.width, info.height), (1000, 600));
        // The legend column (right of the chart) has drawn text.
        let w = info.width as usize;
        let dark = (40..120)
            .flat_map(|y| (800..1000).map(move |x| (y * w + x) * 3))
            .filter(|o| px[*o] < 100)
            .count();
        assert!(dark > 10, "no legend text drawn");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
