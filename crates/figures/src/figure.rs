//! What every figure the program draws shares: numbers rounded to what the picture
//! resolves, and text measured in the embedded DejaVu Sans so a caption wraps before it
//! leaves the image. The plots (map, energy, predictability, comparison) and the animations
//! all format and wrap through here.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use std::sync::OnceLock;

/// Decimals that show a quantity resolved to `resolution` (a grid's spacing, a tick step):
/// one significant digit of the resolution, never fewer than none.
pub(crate) fn decimals_for(resolution: f64) -> usize {
    if !(resolution.is_finite() && resolution > 0.0) {
        return 0;
    }
    // The nudge keeps an exact 0.1 (log₁₀ a hair under −1) at one decimal.
    (-(resolution.log10() + 1e-9).floor()).clamp(0.0, 15.0) as usize
}

/// `value` to `decimals` places, without a minus sign on a zero ("-0.0" reads as a defect).
pub(crate) fn fixed(value: f64, decimals: usize) -> String {
    let s = format!("{value:.decimals$}");
    if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
        s.trim_start_matches('-').to_string()
    } else {
        s
    }
}

/// `value` as far as `resolution` resolves it: `-14.204545454545455` on a grid 0.94 apart
/// reads `-14.2`.
pub(crate) fn resolved(value: f64, resolution: f64) -> String {
    fixed(value, decimals_for(resolution))
}

/// The labels of an axis's ticks: plotters puts at most `count` of them on multiples of 1,
/// 2 or 5 × 10ⁿ; every label gets the decimals of that step, so `120000` never reads
/// `120000.0` and `0.25` never `0.25000000000000006`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ticks {
    pub(crate) count: usize,
    decimals: usize,
}

impl Ticks {
    /// The ticks of the range `lo..hi` with at most `count` labels.
    pub(crate) fn new(lo: f64, hi: f64, count: usize) -> Ticks {
        Ticks {
            count,
            decimals: decimals_for(nice_step(lo, hi, count)),
        }
    }

    /// The tick values of `lo..hi` a colour bar marks: the multiples of the step inside
    /// the range.
    pub(crate) fn values(lo: f64, hi: f64, count: usize) -> (Ticks, Vec<f64>) {
        let step = nice_step(lo, hi, count);
        let ticks = Ticks {
            count,
            decimals: decimals_for(step),
        };
        if !(lo.is_finite() && hi.is_finite()) || hi < lo {
            return (ticks, Vec::new());
        }
        let first = (lo / step - 1e-9).ceil() as i64;
        let last = (hi / step + 1e-9).floor() as i64;
        (ticks, (first..=last).map(|k| k as f64 * step).collect())
    }

    /// A tick's label.
    pub(crate) fn label(&self, value: f64) -> String {
        if value != 0.0 && value.abs() >= 1e6 {
            // 2500000 → 2.5e6: past a million, digits stop being readable.
            let s = format!("{value:.2e}");
            let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
            let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
            return format!("{mantissa}e{exp}");
        }
        fixed(value, self.decimals)
    }
}

/// The finest step of 1, 2 or 5 × 10ⁿ whose multiples inside `lo..hi` are at most `count`
/// (plotters' rule for its tick marks).
fn nice_step(lo: f64, hi: f64, count: usize) -> f64 {
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) || count < 2 {
        return 1.0;
    }
    let fits = |step: f64| ((hi / step + 1e-9).floor() - (lo / step - 1e-9).ceil() + 1.0) <= count as f64;
    let mut decade = 10f64.powf((span / count as f64).log10().floor() - 1.0);
    loop {
        for m in [1.0, 2.0, 5.0] {
            if fits(m * decade) {
                return m * decade;
            }
        }
        decade *= 10.0;
    }
}

/// A setup value in a caption: at most six significant digits, no trailing zeros
/// (`0.005`, `500000`, `1.2`).
pub fn setup_value(value: f64) -> String {
    if !value.is_finite() {
        return format!("{value}");
    }
    if value == 0.0 {
        return "0".to_string();
    }
    let magnitude = value.abs().log10().floor() as i32;
    if !(-4..9).contains(&magnitude) {
        let s = format!("{value:.5e}");
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exp}");
    }
    let decimals = (5 - magnitude).max(0) as usize;
    let s = fixed(value, decimals);
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// DejaVu Sans 2.37, regular and bold, cut to the scripts and symbols a figure writes
/// (`fonts/README.md` says which and how): 0.3 MB of the 1.4 MB the whole fonts are.
pub(crate) const DEJAVU_SANS: [&[u8]; 2] = [
    include_bytes!("../fonts/DejaVuSans.ttf"),
    include_bytes!("../fonts/DejaVuSans-Bold.ttf"),
];

/// The embedded DejaVu Sans, regular and bold, as plotters draws it.
fn fonts() -> &'static [FontRef<'static>; 2] {
    static FONTS: OnceLock<[FontRef<'static>; 2]> = OnceLock::new();
    FONTS.get_or_init(|| {
        DEJAVU_SANS
            .map(|bytes| FontRef::try_from_slice(bytes).expect("the embedded DejaVu Sans is a valid font"))
    })
}

/// The font for `bold` or regular text.
pub(crate) fn font(bold: bool) -> &'static FontRef<'static> {
    &fonts()[usize::from(bold)]
}

/// Pixels `text` takes across at `px` pixels per em, as plotters lays it out (advances and
/// kerning).
pub(crate) fn text_width(text: &str, px: f64, bold: bool) -> f64 {
    let font = font(bold).as_scaled(PxScale::from(px as f32));
    let mut width = 0.0f32;
    let mut previous = None;
    for c in text.chars() {
        let id = font.glyph_id(c);
        if let Some(p) = previous {
            width += font.kern(p, id);
        }
        width += font.h_advance(id);
        previous = Some(id);
    }
    f64::from(width)
}

/// `text` broken at spaces into lines no wider than `max_width` pixels at `px` (a single
/// word longer than that is broken between characters, so no line ever is).
pub(crate) fn wrap(text: &str, px: f64, max_width: f64, bold: bool) -> Vec<String> {
    let fits = |s: &str| text_width(s, px, bold) <= max_width;
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split(' ').filter(|w| !w.is_empty()) {
        let joined = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if fits(&joined) {
            line = joined;
            continue;
        }
        if !line.is_empty() {
            lines.push(std::mem::take(&mut line));
        }
        // A word wider than the line on its own: cut it where it must be.
        let mut rest = word.to_string();
        while !fits(&rest) {
            let mut cut = String::new();
            for c in rest.chars() {
                let mut next = cut.clone();
                next.push(c);
                if !fits(&next) && !cut.is_empty() {
                    break;
                }
                cut = next;
            }
            rest = rest[cut.len()..].to_string();
            lines.push(cut);
            if rest.is_empty() {
                break;
            }
        }
        line = rest;
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_resolves_one_significant_digit_of_its_spacing() {
        // The axis: 9 nodes from -14.2045… to -6.7045…, 0.9375 apart.
        assert_eq!(resolved(-14.204545454545455, 0.9375), "-14.2");
        assert_eq!(resolved(-6.704545454545455, 0.9375), "-6.7");
        assert_eq!(resolved(40.0, 2.0), "40");
        assert_eq!(resolved(0.1 + 0.2, 0.1), "0.3");
        assert_eq!(resolved(-0.01, 0.5), "0.0");
        assert_eq!(decimals_for(0.001), 3);
        assert_eq!(decimals_for(1e-12), 12);
    }

    #[test]
    fn tick_labels_carry_the_decimals_of_their_step() {
        let t = Ticks::new(0.0, 140000.0, 10);
        assert_eq!(t.label(120000.0), "120000");
        let t = Ticks::new(0.0, 1.02, 10);
        assert_eq!(t.label(0.6000000000000001), "0.6");
        let t = Ticks::new(-1.0, 1.0, 5);
        assert_eq!(t.label(0.5), "0.5");
        assert_eq!(t.label(-0.0), "0.0");
        assert_eq!(Ticks::new(0.0, 5e6, 6).label(2.5e6), "2.5e6");
        let (t, values) = Ticks::values(0.429, 1.286, 5);
        assert_eq!(
            values.iter().map(|&v| t.label(v)).collect::<Vec<_>>(),
            ["0.6", "0.8", "1.0", "1.2"]
        );
    }

    #[test]
    fn setup_values_read_as_written() {
        assert_eq!(setup_value(500000.0), "500000");
        assert_eq!(setup_value(0.005), "0.005");
        assert_eq!(setup_value(1.2), "1.2");
        assert_eq!(setup_value(-20.0), "-20");
        assert_eq!(setup_value(0.1 + 0.2), "0.3");
        assert_eq!(setup_value(1e-9), "1e-9");
    }

    #[test]
    fn wrapped_lines_fit_and_keep_every_word() {
        let text = "x initial.angular_velocity.x from -14.2 to -6.7, y ground.friction from 0 to 2; \
                    every other value as below, and a_very_long_word_without_any_space_in_it_at_all";
        let lines = wrap(text, 16.0, 200.0, false);
        assert!(lines.len() > 3, "{lines:?}");
        for line in &lines {
            assert!(text_width(line, 16.0, false) <= 200.0, "{line}");
        }
        assert_eq!(lines.concat().replace(' ', ""), text.replace(' ', ""));
        // Widths grow with the text and the size.
        assert!(text_width("mm", 16.0, false) > text_width("m", 16.0, false));
        assert!(text_width("m", 32.0, false) > 1.9 * text_width("m", 16.0, false));
    }

    /// Every character that the figures' own code, the registry (keys, units, meanings,
    /// labels) or a shipped preset can put in a label or a caption is in both embedded fonts:
    /// the cut-down fonts would draw a missing one as an empty box.
    #[test]
    fn the_embedded_fonts_have_every_character_a_figure_writes() {
        fn sources(dir: &std::path::Path, text: &mut String) {
            for entry in std::fs::read_dir(dir).expect("the crate's sources") {
                let path = entry.expect("a folder entry").path();
                if path.is_dir() {
                    sources(&path, text);
                } else if path.extension().is_some_and(|e| e == "rs") {
                    text.push_str(&std::fs::read_to_string(&path).expect("a source file"));
                }
            }
        }
        let mut text = String::new();
        sources(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
            &mut text,
        );
        for spec in dicesim_setup::registry::ALL {
            text.extend([spec.key(), spec.limits.unit, spec.comment]);
            text.extend(spec.labels.iter().copied());
        }
        for (_, preset) in dicesim_setup::preset::SHIPPED {
            text.push_str(preset);
        }
        let mut used: Vec<char> = text.chars().filter(|c| !c.is_control()).collect();
        used.sort_unstable();
        used.dedup();
        assert!(
            ['μ', 'Δ', '²', '·'].iter().all(|c| used.contains(c)),
            "the model's symbols were not gathered: {used:?}"
        );
        for bold in [false, true] {
            let missing: String = used.iter().filter(|&&c| font(bold).glyph_id(c).0 == 0).collect();
            assert!(missing.is_empty(), "bold {bold}: no glyph for {missing:?}");
        }
        // And a character the cut leaves out is indeed missing: the check can fail.
        assert_eq!(font(false).glyph_id('\u{4e00}').0, 0);
    }

    /// The `kern` table survived the cut: a kerned pair is narrower than its letters apart.
    #[test]
    fn the_embedded_fonts_kern() {
        for bold in [false, true] {
            let apart = text_width("A", 16.0, bold) + text_width("V", 16.0, bold);
            assert!(text_width("AV", 16.0, bold) < apart - 0.5, "bold {bold}");
        }
    }
}
