//! Basin maps as PNG or SVG images a teacher can put on a slide.
//!
//! Text is measured with the DejaVu Sans font embedded in the binary, so drawing needs no
//! system fonts (and the SVG names `sans-serif`, which viewers resolve themselves).

use super::Error;
use super::basin::{BasinMap, Cell, Layer};
use crate::output::Output;
use crate::physics::Status;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::register_font;
use std::sync::OnceLock;

/// Image size in pixels (SVG user units).
pub(crate) const SIZE: (u32, u32) = (1200, 800);
/// Width of the legend strip on the right.
const LEGEND_WIDTH: u32 = 200;

/// Okabe–Ito colours for faces 1..6: distinguishable with the common colour-vision deficiencies.
pub(crate) const FACE_COLOURS: [RGBColor; 6] = [
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 158, 115),
    RGBColor(240, 228, 66),
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
];
const NO_FACE: RGBColor = RGBColor(200, 200, 200);
const TIMEOUT: RGBColor = RGBColor(90, 90, 90);
const UNSTABLE: RGBColor = RGBColor(204, 121, 167);
const UNKNOWN: RGBColor = WHITE;

/// Viridis at 0, ¼, ½, ¾, 1: a perceptually even scale for settle times.
const VIRIDIS: [RGBColor; 5] = [
    RGBColor(68, 1, 84),
    RGBColor(59, 82, 139),
    RGBColor(33, 145, 140),
    RGBColor(94, 201, 98),
    RGBColor(253, 231, 37),
];

fn viridis(t: f64) -> RGBColor {
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let x = t * (VIRIDIS.len() - 1) as f64;
    let k = (x.floor() as usize).min(VIRIDIS.len() - 2);
    let f = x - k as f64;
    let (a, b) = (VIRIDIS[k], VIRIDIS[k + 1]);
    let mix = |p: u8, q: u8| (p as f64 + (q as f64 - p as f64) * f).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

pub(crate) fn register_fonts() -> Result<(), Error> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
                .and_then(|_| register_font("sans-serif", FontStyle::Bold, dejavu::sans::bold()))
                .map_err(|_| "the embedded DejaVu Sans font is not a valid font".to_string())
        })
        .clone()
        .map_err(Error::Plot)
}

pub(crate) fn plot_error(e: impl std::fmt::Display) -> Error {
    Error::Plot(e.to_string())
}

/// An image file format the plots are drawn in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ImageFormat {
    Png,
    Svg,
}

impl ImageFormat {
    /// The format for a file extension (`png` or `svg`, any case).
    pub(crate) fn from_extension(extension: &str) -> Option<ImageFormat> {
        match extension.to_ascii_lowercase().as_str() {
            "png" => Some(ImageFormat::Png),
            "svg" => Some(ImageFormat::Svg),
            _ => None,
        }
    }
}

/// Draws with `draw` on a PNG canvas of `size` pixels and returns the encoded file. Drawing
/// into memory keeps every write error with the one place that writes files.
pub(crate) fn png_bytes(
    size: (u32, u32),
    draw: impl FnOnce(DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), Error>,
) -> Result<Vec<u8>, Error> {
    use image::ImageEncoder;
    let mut pixels = vec![0u8; size.0 as usize * size.1 as usize * 3];
    draw(BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area())?;
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(&pixels, size.0, size.1, image::ColorType::Rgb8)
        .map_err(plot_error)?;
    Ok(png)
}

/// Writes `map` to `out` as a PNG or SVG image, by its extension; nothing is written if
/// drawing fails.
pub(crate) fn write_image(map: &BasinMap, layer: Layer, out: &Output) -> Result<(), Error> {
    let format = ImageFormat::from_extension(out.extension())
        .ok_or_else(|| Error::Plot(format!("{}: expected a .png or .svg file", out.path().display())))?;
    out.write_bytes(&image_bytes(map, layer, format)?)?;
    Ok(())
}

/// `map` as the bytes of a PNG or SVG file.
pub(crate) fn image_bytes(map: &BasinMap, layer: Layer, format: ImageFormat) -> Result<Vec<u8>, Error> {
    register_fonts()?;
    match format {
        ImageFormat::Png => png_bytes(SIZE, |area| draw(area, map, layer)),
        ImageFormat::Svg => {
            let mut svg = String::new();
            draw(
                SVGBackend::with_string(&mut svg, SIZE).into_drawing_area(),
                map,
                layer,
            )?;
            Ok(svg.into_bytes())
        }
    }
}

/// The settle-time scale: s, over settled cells (`None` if none settled).
pub(crate) fn time_range(map: &BasinMap) -> Option<(f64, f64)> {
    let times = map
        .cells
        .iter()
        .flatten()
        .filter(|c| c.outcome.status == Status::Settled)
        .map(|c| c.outcome.time_s);
    times.fold(None, |r, t| match r {
        None => Some((t, t)),
        Some((lo, hi)) => Some((t.min(lo), t.max(hi))),
    })
}

/// A cell's colour in the image; the explorer draws its map in the same colours.
pub(crate) fn cell_colour(cell: Option<&Cell>, layer: Layer, times: Option<(f64, f64)>) -> RGBColor {
    let Some(c) = cell else { return UNKNOWN };
    match (c.outcome.status, c.outcome.face, layer) {
        (Status::Timeout, ..) => TIMEOUT,
        (Status::Unstable, ..) => UNSTABLE,
        (Status::Settled, None, Layer::Face) => NO_FACE,
        (Status::Settled, Some(f), Layer::Face) => FACE_COLOURS[f as usize - 1],
        (Status::Settled, _, Layer::SettleTime) => {
            let (lo, hi) = times.unwrap_or((0.0, 1.0));
            viridis((c.outcome.time_s - lo) / (hi - lo).max(1e-12))
        }
    }
}

fn title(map: &BasinMap, layer: Layer) -> String {
    let what = match layer {
        Layer::Face => "Face up",
        Layer::SettleTime => "Settle time",
    };
    let (w, h) = (map.width(), map.height());
    let how = match map.method {
        super::basin::Method::Uniform => format!("uniform grid {w}×{h}"),
        super::basin::Method::Adaptive => {
            format!("adaptive {w}×{h}, {} of {} cells rolled", map.sampled, w * h)
        }
    };
    format!("{what} — {how}")
}

fn axis_title(axis: &super::basin::Axis) -> String {
    format!("{}: {} to {}", axis.key.label(), axis.min, axis.max)
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, map: &BasinMap, layer: Layer) -> Result<(), Error> {
    root.fill(&WHITE).map_err(plot_error)?;
    let (area, legend) = root.split_horizontally(SIZE.0 - LEGEND_WIDTH);
    let times = time_range(map);
    let (x, y) = (&map.x, &map.y);
    let (dx, dy) = (x.spacing(), y.spacing());
    let x_range = (x.min - dx / 2.0)..(x.max + dx / 2.0);
    let mut chart = ChartBuilder::on(&area);
    chart
        .caption(title(map, layer), ("sans-serif", 26))
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(80);
    let label_style = ("sans-serif", 16);
    let desc_style = ("sans-serif", 19);
    if map.height() == 1 {
        // A 1-D scan: settle time against the value, each point in its face's colour, as the
        // authors plotted it (the time spikes at the borders between faces).
        let hi = times.map_or(1.0, |t| t.1) * 1.05;
        let mut chart = chart.build_cartesian_2d(x_range, 0.0..hi).map_err(plot_error)?;
        chart
            .configure_mesh()
            .x_desc(axis_title(x))
            .y_desc(format!("settle time (s), {} = {}", y.key.label(), y.value(0)))
            .label_style(label_style)
            .axis_desc_style(desc_style)
            .draw()
            .map_err(plot_error)?;
        let points: Vec<(f64, f64, RGBColor)> = (0..map.width())
            .filter_map(|i| {
                let c = map.cell(i, 0)?;
                Some((
                    x.value(i),
                    c.outcome.time_s,
                    cell_colour(Some(c), Layer::Face, times),
                ))
            })
            .collect();
        chart
            .draw_series(std::iter::once(PathElement::new(
                points.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>(),
                RGBColor(160, 160, 160),
            )))
            .map_err(plot_error)?;
        chart
            .draw_series(
                points
                    .iter()
                    .map(|&(px, py, c)| Circle::new((px, py), 3, c.filled())),
            )
            .map_err(plot_error)?;
        face_legend(&legend, map)?;
    } else {
        let y_range = (y.min - dy / 2.0)..(y.max + dy / 2.0);
        let mut chart = chart.build_cartesian_2d(x_range, y_range).map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(axis_title(x))
            .y_desc(axis_title(y))
            .label_style(label_style)
            .axis_desc_style(desc_style)
            .draw()
            .map_err(plot_error)?;
        // One rectangle per run of equal colour along a row keeps the SVG small.
        let mut runs = Vec::new();
        for j in 0..map.height() {
            let mut i = 0;
            while i < map.width() {
                let colour = cell_colour(map.cell(i, j), layer, times);
                let start = i;
                while i + 1 < map.width() && cell_colour(map.cell(i + 1, j), layer, times) == colour {
                    i += 1;
                }
                let (yc, xa, xb) = (y.value(j), x.value(start), x.value(i));
                runs.push(Rectangle::new(
                    [(xa - dx / 2.0, yc - dy / 2.0), (xb + dx / 2.0, yc + dy / 2.0)],
                    colour.filled(),
                ));
                i += 1;
            }
        }
        chart.draw_series(runs).map_err(plot_error)?;
        match layer {
            Layer::Face => face_legend(&legend, map)?,
            Layer::SettleTime => time_legend(&legend, map, times)?,
        }
    }
    root.present().map_err(plot_error)
}

/// Faces 1..6, then whichever other endings occur.
fn face_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, map: &BasinMap) -> Result<(), Error> {
    let occurs = |status: Status, face: Option<u8>| {
        map.cells
            .iter()
            .flatten()
            .any(|c| c.outcome.status == status && (status != Status::Settled || c.outcome.face == face))
    };
    let mut entries: Vec<(String, RGBColor)> = (0..6)
        .map(|f| (format!("face {}", f + 1), FACE_COLOURS[f]))
        .collect();
    if occurs(Status::Settled, None) {
        entries.push(("no face (corner)".to_string(), NO_FACE));
    }
    if occurs(Status::Timeout, None) {
        entries.push(("did not settle".to_string(), TIMEOUT));
    }
    if occurs(Status::Unstable, None) {
        entries.push(("unstable".to_string(), UNSTABLE));
    }
    for (k, (label, colour)) in entries.iter().enumerate() {
        let top = 80 + 34 * k as i32;
        area.draw(&Rectangle::new([(10, top), (36, top + 24)], colour.filled()))
            .map_err(plot_error)?;
        area.draw(&Text::new(label.as_str(), (46, top + 3), ("sans-serif", 18)))
            .map_err(plot_error)?;
    }
    Ok(())
}

/// A vertical colour bar from the shortest (bottom) to the longest (top) settle time.
fn time_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    map: &BasinMap,
    times: Option<(f64, f64)>,
) -> Result<(), Error> {
    let (lo, hi) = times.unwrap_or((0.0, 0.0));
    let (top, bottom) = (90, 600);
    area.draw(&Text::new("settle time (s)", (10, top - 40), ("sans-serif", 18)))
        .map_err(plot_error)?;
    for py in top..bottom {
        let t = (bottom - py) as f64 / (bottom - top) as f64;
        area.draw(&Rectangle::new([(10, py), (40, py + 1)], viridis(t).filled()))
            .map_err(plot_error)?;
    }
    for k in 0..=4 {
        let f = k as f64 / 4.0;
        let py = bottom - ((bottom - top) as f64 * f) as i32;
        let label = format!("{:.3}", lo + (hi - lo) * f);
        area.draw(&Text::new(label, (48, py - 8), ("sans-serif", 16)))
            .map_err(plot_error)?;
    }
    let mut k = 0;
    for (label, colour, status) in [
        ("did not settle", TIMEOUT, Status::Timeout),
        ("unstable", UNSTABLE, Status::Unstable),
    ] {
        if map.cells.iter().flatten().any(|c| c.outcome.status == status) {
            let y = bottom + 30 + 34 * k;
            area.draw(&Rectangle::new([(10, y), (36, y + 24)], colour.filled()))
                .map_err(plot_error)?;
            area.draw(&Text::new(label, (46, y + 3), ("sans-serif", 18)))
                .map_err(plot_error)?;
            k += 1;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_ends_and_middle() {
        assert_eq!(viridis(0.0), VIRIDIS[0]);
        assert_eq!(viridis(1.0), VIRIDIS[4]);
        assert_eq!(viridis(0.5), VIRIDIS[2]);
        assert_eq!(viridis(f64::NAN), VIRIDIS[0]);
    }
}
