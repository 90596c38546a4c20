//! A joint fit of several keys as a PNG image: the deviance surface as heat maps, one per
//! pair of keys. With more than two keys, each cell shows the profile deviance — the lowest
//! over the other keys' values — so a cell inside the 95 % region holds at least one point
//! of it. The region's cells are outlined and the best point is marked.

use crate::figure::{Ticks, setup_value};
use crate::plot::{Record, Scale, plot_error, png_bytes, register_fonts, viridis, with_caption};
use dicesim_experiment::Error;
use dicesim_experiment::compare_joint::{JointComparison, JointSpec};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::preset::Preset;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Image size in pixels.
const SIZE: (u32, u32) = (1400, 760);

/// The heat maps' colour spans this many times the region's rise above the lowest
/// deviance; a cell further above it takes the scale's end.
const COLOUR_SPAN_RISES: f64 = 4.0;

/// The joint fit as the bytes of a PNG file; `record` is captioned and written into it.
pub fn joint_png(comparison: &JointComparison, record: &Record) -> Result<Vec<u8>, Error> {
    register_fonts()?;
    png_bytes(SIZE, record, |root| {
        root.fill(&WHITE).map_err(plot_error)?;
        let picture = with_caption(&root, record, Scale::ONE)?;
        let k = comparison.keys.len();
        let pairs: Vec<(usize, usize)> = (0..k).flat_map(|i| (i + 1..k).map(move |j| (i, j))).collect();
        let panels = picture.split_evenly((1, pairs.len().max(1)));
        for (panel, &(i, j)) in panels.iter().zip(&pairs) {
            draw_surface(panel, comparison, i, j)?;
        }
        root.present().map_err(plot_error)
    })
}

/// The key's name with its unit, for an axis.
fn axis_name(key: &str) -> String {
    match ScanKey::named(key).map(|k| k.unit()) {
        Ok(unit) if !unit.is_empty() => format!("{key} ({unit})"),
        _ => key.to_string(),
    }
}

/// The distinct values of key `k` over the grid, in order.
fn key_values(c: &JointComparison, k: usize) -> Vec<f64> {
    let mut values: Vec<f64> = c.points.iter().map(|p| p.values[k]).collect();
    values.sort_by(f64::total_cmp);
    values.dedup();
    values
}

/// The heat map of keys `i` (across) and `j` (up): each cell the lowest deviance of the
/// points kept there (over every other key's values), outlined when inside the region.
fn draw_surface(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    c: &JointComparison,
    i: usize,
    j: usize,
) -> Result<(), Error> {
    let (xs, ys) = (key_values(c, i), key_values(c, j));
    let half_step = |v: &[f64]| match v {
        [a, b, ..] => 0.5 * (b - a),
        _ => 0.5,
    };
    let (hx, hy) = (half_step(&xs), half_step(&ys));
    let (x0, x1) = (xs[0] - hx, xs[xs.len() - 1] + hx);
    let (y0, y1) = (ys[0] - hy, ys[ys.len() - 1] + hy);
    let lowest = c.lowest_deviance.unwrap_or(0.0);
    let limit = lowest + c.region_rise;
    // With more than two keys, the others' names: each cell is the lowest over them.
    let others: Vec<&str> = (0..c.keys.len())
        .filter(|&k| k != i && k != j)
        .map(|k| c.keys[k].as_str())
        .collect();
    let title = if others.is_empty() {
        "the deviance".to_string()
    } else {
        format!("the lowest over {}", others.join(", "))
    };
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 17))
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(80)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(plot_error)?;
    let (xt, yt) = (
        Ticks::new(xs[0], xs[xs.len() - 1], xs.len()),
        Ticks::new(ys[0], ys[ys.len() - 1], ys.len()),
    );
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(axis_name(&c.keys[i]))
        .y_desc(axis_name(&c.keys[j]))
        .x_labels(xs.len())
        .y_labels(ys.len())
        .x_label_formatter(&|v| xt.label(*v))
        .y_label_formatter(&|v| yt.label(*v))
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()
        .map_err(plot_error)?;
    let best = c.best_point().map(|b| (b.values[i], b.values[j]));
    for &x in &xs {
        for &y in &ys {
            // The profile: the lowest kept deviance of the points at (x, y).
            let profile = c
                .points
                .iter()
                .filter(|p| p.values[i] == x && p.values[j] == y && p.excluded.is_none())
                .filter_map(|p| p.deviance)
                .fold(f64::INFINITY, f64::min);
            let cell = [(x - hx, y - hy), (x + hx, y + hy)];
            let colour = if profile.is_finite() {
                viridis((profile - lowest) / (COLOUR_SPAN_RISES * c.region_rise))
            } else {
                RGBColor(200, 200, 200)
            };
            chart
                .draw_series(std::iter::once(Rectangle::new(cell, colour.filled())))
                .map_err(plot_error)?;
            if profile <= limit {
                let inset = [(x - 0.93 * hx, y - 0.93 * hy), (x + 0.93 * hx, y + 0.93 * hy)];
                chart
                    .draw_series(std::iter::once(Rectangle::new(inset, WHITE.stroke_width(3))))
                    .map_err(plot_error)?;
            }
            let text = if profile.is_finite() {
                format!("{profile:.1}")
            } else {
                "left out".to_string()
            };
            let ink = if profile.is_finite() && (profile - lowest) < 0.6 * COLOUR_SPAN_RISES * c.region_rise {
                WHITE
            } else {
                BLACK
            };
            let marked = if best == Some((x, y)) {
                format!("best {text}")
            } else {
                text
            };
            chart
                .draw_series(std::iter::once(Text::new(
                    marked,
                    (x - 0.7 * hx, y),
                    ("sans-serif", 15).into_font().color(&ink),
                )))
                .map_err(plot_error)?;
        }
    }
    Ok(())
}

/// The PNG's caption: the grid, the throws of both experiments, the best point and the
/// region's extent along each key.
pub fn joint_record(
    c: &JointComparison,
    preset: &Preset,
    spec: &JointSpec,
    provenance: &serde_json::Value,
) -> Record {
    let n = setup_value;
    let grid: Vec<String> = spec.keys.iter().map(|k| format!("--fit {}", k.text())).collect();
    let ratios: Vec<String> = spec.calibrate_on.iter().map(|r| n(*r)).collect();
    let best = match (c.best_point(), c.lowest_deviance) {
        (Some(b), Some(d)) => format!(
            "best point {} (deviance {d:.2}: Budden {:.2}, shaved die {:.2})",
            spec.point_text(&b.values),
            b.budden_deviance.unwrap_or(f64::NAN),
            b.shaved_deviance.unwrap_or(f64::NAN)
        ),
        _ => "no best point".to_string(),
    };
    let region: Vec<String> = c
        .region_ranges
        .iter()
        .map(|r| {
            format!(
                "{} {} to {}{}",
                r.key,
                n(r.low),
                n(r.high),
                if r.low_open || r.high_open { " (open)" } else { "" }
            )
        })
        .collect();
    let left_out = c.points.iter().filter(|p| p.excluded.is_some()).count();
    let caption = vec![
        format!(
            "{}: {} over {} grid points, each with the same throws (seed {}): Budden's ratios {} as he threw them, \
             the shaved die at {} {} times paired with the uncut die; {left_out} points left out",
            preset.name,
            grid.join(" "),
            c.points.len(),
            spec.seed,
            ratios.join(", "),
            n(c.cut),
            spec.shaved_throws,
        ),
        format!(
            "{best}; 95 % region ({} points within {:.2}, χ² of {} degrees of freedom, outlined): {}; colour: dark at the lowest, yellow {:.1} above it (every value in the file's dicesim-provenance text)",
            c.region.len(),
            c.region_rise,
            c.keys.len(),
            region.join(", "),
            COLOUR_SPAN_RISES * c.region_rise
        ),
    ];
    let title = format!(
        "{}: a joint fit to Budden's cuboids and the shaved die",
        preset.name
    );
    Record::captioned(title, caption, dicesim_experiment::PROGRAM).with_provenance(provenance)
}
