//! A roll's energy against time as a PNG image, the explorer's energy plot on paper: the
//! four forms and their total, with the stopping threshold dotted, on the explorer's linear
//! or log scale, and the setup in a caption and in the file's text chunks.

use crate::figure::Ticks;
use crate::plot::{Record, Scale, TICKS, plot_error, png_bytes, register_fonts, with_caption};
use dicesim_experiment::Error;
use dicesim_physics::Energy;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Image size in pixels.
pub(crate) const SIZE: (u32, u32) = (1200, 700);

/// Names and colours of the series, in the explorer's order: total, translational,
/// rotational, gravitational, elastic.
const SERIES: [(&str, RGBColor); 5] = [
    ("total", RGBColor(0, 0, 0)),
    ("translational", RGBColor(0, 114, 178)),
    ("rotational", RGBColor(204, 121, 167)),
    ("gravitational", RGBColor(0, 158, 115)),
    ("elastic", RGBColor(213, 94, 0)),
];

fn value(e: &Energy, series: usize) -> f64 {
    match series {
        0 => e.total(),
        1 => e.translational,
        2 => e.rotational,
        3 => e.gravitational,
        _ => e.elastic,
    }
}

/// erg: the floor of the log scale (energies below it, negative gravity too, sit on it), as
/// on the explorer's plot.
const LOG_FLOOR: f64 = 1.0;

/// `samples` (s, energy) as the bytes of a PNG file, with the stop threshold (erg) dotted,
/// on a log₁₀ energy axis when `log`; `record` is captioned and written into the file.
pub fn energy_plot_png(
    samples: &[(f64, Energy)],
    threshold: f64,
    log: bool,
    record: &Record,
) -> Result<Vec<u8>, Error> {
    register_fonts()?;
    let title = record
        .text
        .iter()
        .find(|(k, _)| k == "Title")
        .map_or("energy", |(_, t)| t.as_str())
        .to_string();
    png_bytes(SIZE, record, |root| {
        root.fill(&WHITE).map_err(plot_error)?;
        let picture = with_caption(&root, record, Scale::ONE)?;
        draw(&picture, samples, threshold, log, &title)
    })
}

fn draw(
    root: &DrawingArea<BitMapBackend<'_>, Shift>,
    samples: &[(f64, Energy)],
    threshold: f64,
    log: bool,
    title: &str,
) -> Result<(), Error> {
    // On the log scale every value is drawn as log₁₀ of itself (floored), and the axis
    // labels the whole decades.
    let y = |v: f64| if log { v.max(LOG_FLOOR).log10() } else { v };
    let t_end = samples.last().map_or(1.0, |s| s.0).max(1e-3);
    // A table too soft to hold a face has no threshold (−∞): nothing to draw.
    let shown = threshold.is_finite().then_some(y(threshold));
    // 0 erg on the linear scale, 1 erg (10⁰) on the log one.
    let (mut lo, mut hi) = (0.0f64, shown.unwrap_or(1.0));
    for (_, e) in samples {
        for k in 0..SERIES.len() {
            let v = y(value(e, k));
            if v.is_finite() {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
    }
    let (y_range, decades) = if log {
        let top = hi.max(lo + 1.0).ceil();
        (lo.floor()..top, (top - lo.floor()) as usize)
    } else {
        (lo..hi * 1.05, 0)
    };
    let (xt, yt) = (
        Ticks::new(0.0, t_end, TICKS),
        Ticks::new(y_range.start, y_range.end, TICKS),
    );
    let mut chart = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 26))
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(100)
        .build_cartesian_2d(0.0..t_end, y_range)
        .map_err(plot_error)?;
    let decade = |v: &f64| {
        if (v - v.round()).abs() < 1e-9 {
            let e = v.round() as i32;
            if (0..6).contains(&e) {
                format!("{}", 10f64.powi(e))
            } else {
                format!("1e{e}")
            }
        } else {
            String::new()
        }
    };
    let mut mesh = chart.configure_mesh();
    let (x_label, y_label) = (|v: &f64| xt.label(*v), |v: &f64| yt.label(*v));
    mesh.x_labels(TICKS)
        .x_label_formatter(&x_label)
        .x_desc("time (s)")
        .y_desc(if log {
            "energy (erg, log scale)"
        } else {
            "energy (erg)"
        })
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 19));
    if log {
        mesh.y_labels(decades + 1).y_label_formatter(&decade);
    } else {
        mesh.y_labels(TICKS).y_label_formatter(&y_label);
    }
    mesh.draw().map_err(plot_error)?;
    for (k, (name, colour)) in SERIES.iter().enumerate() {
        let width = if k == 0 { 3 } else { 2 };
        chart
            .draw_series(std::iter::once(PathElement::new(
                samples
                    .iter()
                    .map(|(t, e)| (*t, y(value(e, k))))
                    .collect::<Vec<_>>(),
                colour.stroke_width(width),
            )))
            .map_err(plot_error)?
            .label(*name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(3)));
    }
    if let Some(threshold) = shown {
        let dots = (0..200).map(|i| (t_end * i as f64 / 199.0, threshold));
        chart
            .draw_series(dots.map(|p| Circle::new(p, 1, BLACK.filled())))
            .map_err(plot_error)?
            .label("stop threshold")
            .legend(|(x, y)| Circle::new((x + 12, y), 2, BLACK.filled()));
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 17))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(plot_error)?;
    root.present().map_err(plot_error)
}
