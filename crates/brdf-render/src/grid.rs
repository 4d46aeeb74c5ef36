//! Labelled PNG grids of renderings (Kurt's Figures 9.1-9.3, the dense
//! materials, Sopp's preview strips): a title, column and row labels, each
//! tile tone mapped and its exposure stated, difference tiles in a colour
//! map with a colour bar. Text is drawn with the font bundled in the binary
//! ([`font`]), so no system font is needed.

use std::path::Path;
use std::sync::Once;

use plotters::prelude::*;

use crate::Image;
use crate::RenderError;

/// The bundled font (DejaVu Sans; licence beside it in `assets/fonts`).
pub static FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// Register the bundled font as plotters' `sans-serif` (once).
pub fn font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The font is compiled in and known to parse (tested); a failure
        // would leave text undrawn, which the plotting calls then report.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// How a tile is shown.
#[derive(Clone, Debug)]
pub enum Tone {
    /// Linear values times `exposure`, clamped to `[0, 1]`, gamma 2.2.
    Exposure(f64),
    /// `|difference|` (mean over channels) from 0 to `max` in the Viridis
    /// colour map, with a colour bar.
    Difference(f64),
}

/// One tile: an image and its tone mapping.
#[derive(Clone, Debug)]
pub struct Tile {
    /// The linear image.
    pub image: Image,
    /// Tone mapping.
    pub tone: Tone,
}

/// A labelled grid of tiles.
#[derive(Clone, Debug, Default)]
pub struct Grid {
    /// Title line.
    pub title: String,
    /// Column labels.
    pub columns: Vec<String>,
    /// Row labels (each may have a second line, after `\n`).
    pub rows: Vec<String>,
    /// `tiles[row][column]` (`None` leaves a blank).
    pub tiles: Vec<Vec<Option<Tile>>>,
    /// Lines under the grid (tone mapping, what the tiles are).
    pub footer: Vec<String>,
}

/// The exposure that maps the `q`-quantile of the non-zero values of
/// `img` to 0.8 (so a small highlight does not leave the rest black).
pub fn exposure_for(img: &Image, q: f64) -> f64 {
    let mut v: Vec<f64> = img
        .data
        .iter()
        .copied()
        .filter(|x| x.is_finite() && *x > 0.0)
        .collect();
    if v.is_empty() {
        return 1.0;
    }
    v.sort_by(f64::total_cmp);
    let k = ((v.len() - 1) as f64 * q).round() as usize;
    0.8 / v[k].max(1e-300)
}

/// The colour-bar maximum of difference tiles: the 99th percentile of
/// their non-zero values (one wild pixel, e.g. a model's spike at grazing
/// angles, must not leave the rest of the map uniformly dark; larger
/// differences saturate).
pub fn difference_scale(images: &[Image]) -> f64 {
    let mut v: Vec<f64> = images
        .iter()
        .flat_map(|i| i.data.iter().copied())
        .filter(|x| x.is_finite() && *x > 0.0)
        .collect();
    if v.is_empty() {
        return 1.0;
    }
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * 0.99).round() as usize]
}

fn gamma(v: f64) -> u8 {
    (v.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8
}

/// Viridis (matplotlib's perceptually uniform map) at nine stops,
/// linearly interpolated between them.
const VIRIDIS: [[f64; 3]; 9] = [
    [68.0, 1.0, 84.0],
    [71.0, 44.0, 122.0],
    [59.0, 81.0, 139.0],
    [44.0, 113.0, 142.0],
    [33.0, 144.0, 141.0],
    [39.0, 173.0, 129.0],
    [92.0, 200.0, 99.0],
    [170.0, 220.0, 50.0],
    [253.0, 231.0, 37.0],
];

fn viridis(t: f64) -> [u8; 3] {
    let x = if t.is_finite() {
        t.clamp(0.0, 1.0) * 8.0
    } else {
        0.0
    };
    let k = (x.floor() as usize).min(7);
    let f = x - k as f64;
    let (a, b) = (VIRIDIS[k], VIRIDIS[k + 1]);
    [0, 1, 2].map(|c| (a[c] + f * (b[c] - a[c])).round() as u8)
}

/// Pixel `(x, y)` of a tile as 8-bit RGB.
fn pixel(t: &Tile, x: usize, y: usize) -> [u8; 3] {
    let img = &t.image;
    let base = (y * img.width + x) * img.channels;
    let px = &img.data[base..base + img.channels];
    match t.tone {
        Tone::Exposure(e) => {
            if img.channels >= 3 {
                [gamma(px[0] * e), gamma(px[1] * e), gamma(px[2] * e)]
            } else {
                let g = gamma(px[0] * e);
                [g, g, g]
            }
        }
        Tone::Difference(max) => {
            let m = px.iter().sum::<f64>() / img.channels.max(1) as f64;
            viridis(m / max.max(1e-300))
        }
    }
}

const LEFT: usize = 170;
const TOP: usize = 64;
const GAP: usize = 8;
const BAR: usize = 70;
const LINE: usize = 18;

impl Grid {
    fn cell(&self) -> (usize, usize) {
        let tiles = self.tiles.iter().flatten().flatten();
        let w = tiles.clone().map(|t| t.image.width).max().unwrap_or(1);
        let h = tiles.map(|t| t.image.height).max().unwrap_or(1);
        (w, h)
    }

    /// Write the grid as an RGB PNG.
    pub fn write_png(&self, path: &Path) -> Result<(), RenderError> {
        font();
        let (cw, ch) = self.cell();
        let ncol = self.tiles.iter().map(Vec::len).max().unwrap_or(0);
        let bar = self
            .tiles
            .iter()
            .flatten()
            .flatten()
            .any(|t| matches!(t.tone, Tone::Difference(_)));
        let width = LEFT + ncol * (cw + GAP) + if bar { BAR } else { GAP } + 10;
        let chars = (width.saturating_sub(16) / 7).max(30);
        let footer: Vec<String> = self.footer.iter().flat_map(|l| wrap(l, chars)).collect();
        let height = TOP + self.tiles.len() * (ch + GAP) + (footer.len() + 1) * LINE;
        let mut buf = vec![255u8; width * height * 3];
        for (r, row) in self.tiles.iter().enumerate() {
            for (c, tile) in row.iter().enumerate() {
                let Some(t) = tile else { continue };
                let (x0, y0) = (LEFT + c * (cw + GAP), TOP + r * (ch + GAP));
                for y in 0..t.image.height {
                    for x in 0..t.image.width {
                        let o = ((y0 + y) * width + x0 + x) * 3;
                        buf[o..o + 3].copy_from_slice(&pixel(t, x, y));
                    }
                }
            }
            if row
                .iter()
                .flatten()
                .any(|t| matches!(t.tone, Tone::Difference(_)))
            {
                let x0 = LEFT + ncol * (cw + GAP);
                let y0 = TOP + r * (ch + GAP);
                for y in 0..ch {
                    let col = viridis(1.0 - y as f64 / (ch - 1).max(1) as f64);
                    for x in 0..12 {
                        let o = ((y0 + y) * width + x0 + x) * 3;
                        buf[o..o + 3].copy_from_slice(&col);
                    }
                }
            }
        }
        self.draw_text(&mut buf, width, height, cw, ch, ncol, &footer)
            .map_err(|e| io_err(path, e))?;
        write_rgb_png(path, width, height, &buf)
    }

    fn draw_text(
        &self,
        buf: &mut [u8],
        width: usize,
        height: usize,
        cw: usize,
        ch: usize,
        ncol: usize,
        footer: &[String],
    ) -> Result<(), String> {
        let root =
            BitMapBackend::with_buffer(buf, (width as u32, height as u32)).into_drawing_area();
        let text = |s: &str, x: usize, y: usize, size: u32| {
            root.draw(&Text::new(
                s.to_string(),
                (x as i32, y as i32),
                ("sans-serif", size).into_font().color(&BLACK),
            ))
            .map_err(|e| e.to_string())
        };
        text(&self.title, 8, 6, 17)?;
        for (c, label) in self.columns.iter().enumerate() {
            let x = LEFT + c * (cw + GAP);
            for (k, part) in wrap(label, cw / 7).iter().enumerate() {
                text(part, x, 30 + k * 14, 12)?;
            }
        }
        for (r, label) in self.rows.iter().enumerate() {
            let y = TOP + r * (ch + GAP) + 4;
            for (k, part) in label.split('\n').enumerate() {
                text(part, 6, y + k * 15, 12)?;
            }
            if let Some(max) = self.tiles[r].iter().flatten().find_map(|t| match t.tone {
                Tone::Difference(m) => Some(m),
                _ => None,
            }) {
                let x = LEFT + ncol * (cw + GAP) + 15;
                text(
                    &format!(">= {}", brdf_core::format::number(max, 2)),
                    x,
                    y - 4,
                    11,
                )?;
                text("0", x, y + ch - 16, 11)?;
                text("|diff|", x, y + ch / 2 - 6, 11)?;
            }
        }
        let y0 = TOP + self.tiles.len() * (ch + GAP) + 2;
        for (k, line) in footer.iter().enumerate() {
            text(line, 8, y0 + k * LINE, 12)?;
        }
        root.present().map_err(|e| e.to_string())?;
        Ok(())
    }
}

/// Split a label into lines of about `chars` characters at spaces.
fn wrap(s: &str, chars: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in s.split(' ') {
        match lines.last_mut() {
            Some(l) if l.len() + 1 + word.len() <= chars.max(6) => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

fn io_err(path: &Path, e: impl std::fmt::Display) -> RenderError {
    RenderError::Io {
        path: path.display().to_string(),
        source: std::io::Error::other(e.to_string()),
    }
}

/// Write an 8-bit RGB buffer as PNG.
pub fn write_rgb_png(
    path: &Path,
    width: usize,
    height: usize,
    rgb: &[u8],
) -> Result<(), RenderError> {
    let file = std::fs::File::create(path).map_err(|e| io_err(path, e))?;
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), width as u32, height as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().map_err(|e| io_err(path, e))?;
    w.write_image_data(rgb).map_err(|e| io_err(path, e))?;
    w.finish().map_err(|e| io_err(path, e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bundled_font_parses_and_a_grid_has_text_and_tiles() {
        assert!(ab_glyph_ok());
        let img = Image {
            width: 20,
            height: 20,
            channels: 1,
            data: vec![0.5; 400],
        };
        let g = Grid {
            title: "T".into(),
            columns: vec!["measured".into(), "difference".into()],
            rows: vec!["felt\nexposure x1.6".into()],
            tiles: vec![vec![
                Some(Tile {
                    image: img.clone(),
                    tone: Tone::Exposure(1.6),
                }),
                Some(Tile {
                    image: img,
                    tone: Tone::Difference(1.0),
                }),
            ]],
            footer: vec!["tone: linear x exposure, gamma 2.2".into()],
        };
        let dir = std::env::temp_dir().join(format!("brdf-grid-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("g.png");
        g.write_png(&p).unwrap();
        let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&p).unwrap()));
        let mut r = dec.read_info().unwrap();
        let mut px = vec![0; r.output_buffer_size().unwrap()];
        let info = r.next_frame(&mut px).unwrap();
        let w = info.width as usize;
        // The exposed tile: 0.5 * 1.6 = 0.8 -> gamma 2.2 -> 230.
        let o = ((TOP + 5) * w + LEFT + 5) * 3;
        assert_eq!(&px[o..o + 3], &[gamma(0.8); 3]);
        // The title was drawn: dark pixels in the first rows.
        assert!(px[..w * 3 * 24].iter().any(|v| *v < 100));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    fn ab_glyph_ok() -> bool {
        plotters::style::register_font("test-sans", FontStyle::Normal, FONT).is_ok()
    }

    #[test]
    fn the_difference_scale_is_the_99th_percentile_of_the_non_zero_values() {
        let img = Image {
            width: 101,
            height: 1,
            channels: 1,
            data: (0..=100).map(f64::from).collect(),
        };
        // Non-zero values 1..=100: index round(99 * 0.99) = 98 holds 99.
        assert_eq!(difference_scale(&[img]), 99.0);
    }

    #[test]
    fn exposure_maps_the_quantile_to_0_8() {
        let img = Image {
            width: 4,
            height: 1,
            channels: 1,
            data: vec![0.0, 1.0, 2.0, 100.0],
        };
        // Non-zero values 1, 2, 100: the median (q = 0.5) is 2.
        assert!((exposure_for(&img, 0.5) - 0.4).abs() < 1e-15);
    }
}
