//! The predictability curves as a PNG image: P(same face) against ε on a log axis, one
//! curve per setup with its 95 % band, its chance level dashed and its ε½ marked.

use crate::figure::{Ticks, setup_value};
use crate::plot::{Record, Scale, TICKS, plot_error, png_bytes, register_fonts, with_caption};
use dicesim_experiment::Error;
use dicesim_experiment::predict::{Prediction, Threshold};
use dicesim_setup::keys::ScanKey;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Image size in pixels.
pub(crate) const SIZE: (u32, u32) = (1200, 760);

/// Colour-blind-safe colours (Okabe–Ito), one per curve, repeating after seven.
const COLOURS: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
];

/// The curves of `prediction` as the bytes of a PNG file; `record` is captioned and written
/// into the file.
pub fn prediction_png(prediction: &Prediction, record: &Record) -> Result<Vec<u8>, Error> {
    register_fonts()?;
    png_bytes(SIZE, record, |root| {
        root.fill(&WHITE).map_err(plot_error)?;
        let picture = with_caption(&root, record, Scale::ONE)?;
        draw(&picture, prediction)
    })
}

/// A curve's name in the legend: the swept value in the explorer's words, with its unit
/// (`drop height = 2 cm`).
fn curve_label(prediction: &Prediction, value: Option<f64>, threshold: Option<Threshold>) -> String {
    let name = match (&prediction.key, value) {
        (Some(key), Some(v)) => match ScanKey::named(key) {
            Ok(k) => k.legend(&setup_value(v)),
            Err(_) => format!("{key} = {}", setup_value(v)),
        },
        _ => "this setup".to_string(),
    };
    match threshold {
        Some(t) => format!("{name}: ε½ {}", t.text()),
        None => name,
    }
}

fn draw(root: &DrawingArea<BitMapBackend<'_>, Shift>, prediction: &Prediction) -> Result<(), Error> {
    let logs: Vec<f64> = prediction.epsilons.iter().map(|e| e.log10()).collect();
    let lo = logs.first().copied().unwrap_or(-15.0).floor();
    let hi = logs.last().copied().unwrap_or(-1.0).ceil().max(lo + 1.0);
    let mut chart = ChartBuilder::on(root)
        .caption(
            "How precisely must the throw be known? P(same face) of a start and its ε-twin",
            ("sans-serif", 24),
        )
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(80)
        .build_cartesian_2d(lo..hi, 0.0..1.02)
        .map_err(plot_error)?;
    let decade = |v: &f64| format!("1e{}", v.round() as i32);
    let yt = Ticks::new(0.0, 1.02, TICKS);
    chart
        .configure_mesh()
        .x_desc("ε, relative change of height, velocity and spin (log scale)")
        .y_desc("P(same face)")
        .x_labels((hi - lo) as usize + 1)
        .x_label_formatter(&decade)
        .y_labels(TICKS)
        .y_label_formatter(&|v| yt.label(*v))
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 19))
        .draw()
        .map_err(plot_error)?;
    for (i, curve) in prediction.curves.iter().enumerate() {
        let colour = COLOURS[i % COLOURS.len()];
        let points: Vec<(f64, f64)> = curve
            .points
            .iter()
            .filter(|p| p.pairs > 0)
            .map(|p| (p.epsilon.log10(), p.same_share))
            .collect();
        // The 95 % band: the upper edge out, the lower edge back.
        let band: Vec<(f64, f64)> = curve
            .points
            .iter()
            .filter(|p| p.pairs > 0)
            .map(|p| (p.epsilon.log10(), p.interval[1]))
            .chain(
                curve
                    .points
                    .iter()
                    .rev()
                    .filter(|p| p.pairs > 0)
                    .map(|p| (p.epsilon.log10(), p.interval[0])),
            )
            .collect();
        chart
            .draw_series(std::iter::once(Polygon::new(band, colour.mix(0.18).filled())))
            .map_err(plot_error)?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(lo, curve.chance), (hi, curve.chance)],
                ShapeStyle::from(colour.mix(0.7)).stroke_width(1),
            )))
            .map_err(plot_error)?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                points.clone(),
                colour.stroke_width(3),
            )))
            .map_err(plot_error)?
            .label(curve_label(prediction, curve.value, curve.threshold))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(3)));
        chart
            .draw_series(points.iter().map(|&p| Circle::new(p, 4, colour.filled())))
            .map_err(plot_error)?;
        if let Some(Threshold::At(e)) = curve.threshold {
            let x = e.log10();
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(x, 0.0), (x, curve.half)],
                    ShapeStyle::from(colour).stroke_width(2),
                )))
                .map_err(plot_error)?;
            chart
                .draw_series(std::iter::once(TriangleMarker::new(
                    (x, curve.half),
                    9,
                    colour.filled(),
                )))
                .map_err(plot_error)?;
        }
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 18))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerLeft)
        .draw()
        .map_err(plot_error)?;
    root.present().map_err(plot_error)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A legend names the swept value in the explorer's words, with its unit.
    #[test]
    fn a_legend_entry_names_the_value_with_its_unit() {
        let prediction = Prediction {
            key: Some("initial.height".to_string()),
            epsilons: vec![1e-3],
            count: 1,
            seed: 1,
            curves: Vec::new(),
            cancelled: false,
        };
        let words = ScanKey::named("initial.height").unwrap().words().to_string();
        assert_eq!(
            curve_label(&prediction, Some(2.0), None),
            format!("{words} = 2 cm")
        );
    }
}
