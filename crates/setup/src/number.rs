//! How a number reads to a person: one formatting for the explorer's panels and the CLI's
//! summaries (a p-value prints as `6.02e-28` in both, never `0.0000`).

/// A number in at most about seven characters: plain when it reads well, else in e-notation.
pub fn fmt_num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let a = v.abs();
    if a == 0.0 {
        "0".to_string()
    } else if !(1e-3..1e6).contains(&a) {
        let s = format!("{v:.2e}");
        // 5.00e5 → 5e5, 1.20e-3 → 1.2e-3
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        format!("{mantissa}e{exp}")
    } else {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    }
}

/// A number a die shows, as a player reads it off the die (docs/dice.md): the d%'s tens
/// with both digits (`00`, `40`, `90`), any other die's number as it is (`0` to `9` on the
/// d10, `20` on the d20).
pub fn die_number(kind: dicesim_physics::Solid, number: u8) -> String {
    match kind {
        dicesim_physics::Solid::Percentile => format!("{number:02}"),
        _ => number.to_string(),
    }
}

/// A number exactly as given, for a value a person typed (a fit's bound, a range's end):
/// the shortest digits that read back as it, with an exponent where a person reads it
/// better (`1e-200`, not a 202-character decimal). The parameter errors' own formatting, so
/// a bound reads the same in a refusal and in a result.
pub use dicesim_physics::params::fmt_number as fmt_exact;

/// A real number as data files write it: the shortest digits that read back as the same
/// double, always with a decimal point or an exponent (`15.0`, `1e-7`, `-0.0`; never `15`),
/// so every reader of a CSV types the column as real in every row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Real(pub f64);

impl Real {
    /// Appends the number's text to `out`: the hot path of a file of millions of rows
    /// (a merge writes and compares every row's reals).
    pub fn write_to(self, out: &mut Vec<u8>) {
        use serde_json::ser::Formatter;
        if self.0.is_finite() {
            // serde_json's shortest round-trip digits (Ryū), with the `.0` kept: several
            // times faster than the standard library's formatting, which a merge spends
            // most of its time in otherwise. Writing into a Vec cannot fail.
            let _ = serde_json::ser::CompactFormatter.write_f64(out, self.0);
        } else {
            out.extend_from_slice(self.0.to_string().as_bytes());
        }
    }
}

impl std::fmt::Display for Real {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut text = Vec::with_capacity(24);
        self.write_to(&mut text);
        f.write_str(std::str::from_utf8(&text).map_err(|_| std::fmt::Error)?)
    }
}

/// Powers of ten a double holds exactly.
const EXACT_POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18,
    1e19, 1e20, 1e21, 1e22,
];

/// The time of a number of steps as files print it: steps × Δt worked out in decimal and
/// rounded to Δt's own decimals, so 684 steps of 0.001 s read `0.684`, not the
/// `0.6840000000000005` the simulation's clock adds up to. The exact count is the `steps`
/// beside it; this is the double nearest to the decimal product.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StepClock {
    /// Δt = `digits` × 10^−`decimals`, `digits` the shortest decimal digits of Δt.
    digits: u64,
    decimals: i32,
}

impl StepClock {
    /// The clock of steps of `dt` s (a positive finite double).
    pub fn new(dt: f64) -> StepClock {
        // `{:e}` is the shortest round-trip form: `1e-3`, `2.5e-4`.
        let text = format!("{dt:e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        let exponent: i32 = exponent.parse().unwrap_or(0);
        let fraction = mantissa.split_once('.').map_or("", |(_, f)| f);
        let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
        StepClock {
            digits: digits.parse().unwrap_or(0),
            decimals: fraction.len() as i32 - exponent,
        }
    }

    /// s, `steps` steps of Δt, rounded to Δt's decimals.
    pub fn time_s(&self, steps: u64) -> f64 {
        let product = u128::from(steps) * u128::from(self.digits);
        if self.decimals <= 0 {
            return product as f64 * 10f64.powi(-self.decimals);
        }
        // Both exact, so one division rounds correctly; past them the decimal is parsed.
        if product < 1 << 53 && self.decimals < EXACT_POWERS_OF_TEN.len() as i32 {
            return product as f64 / EXACT_POWERS_OF_TEN[self.decimals as usize];
        }
        let text = format!("{product}e-{}", self.decimals);
        text.parse().unwrap_or(f64::NAN)
    }
}

/// `bytes` in the unit a person reads (kB, MB, GB; decimal).
pub fn human_bytes(bytes: u64) -> String {
    let b = bytes as f64;
    match bytes {
        0..1_000 => format!("{bytes} B"),
        1_000..1_000_000 => format!("{:.1} kB", b / 1e3),
        1_000_000..1_000_000_000 => format!("{:.1} MB", b / 1e6),
        _ => format!("{:.1} GB", b / 1e9),
    }
}

#[cfg(test)]
mod tests {
    use super::{Real, StepClock, die_number, fmt_exact, fmt_num};

    #[test]
    fn a_percentile_die_reads_with_two_digits_and_every_other_die_as_it_is() {
        use dicesim_physics::Solid;
        assert_eq!(die_number(Solid::Percentile, 0), "00");
        assert_eq!(die_number(Solid::Percentile, 90), "90");
        assert_eq!(die_number(Solid::D10, 0), "0");
        assert_eq!(die_number(Solid::D20, 20), "20");
        assert_eq!(die_number(Solid::Box, 6), "6");
    }

    #[test]
    fn reals_keep_their_point_and_read_back_exactly() {
        assert_eq!(Real(15.0).to_string(), "15.0");
        assert_eq!(Real(-0.0).to_string(), "-0.0");
        assert_eq!(Real(0.1 + 0.2).to_string(), "0.30000000000000004");
        assert_eq!(Real(1e-7).to_string(), "1e-7");
        // The exponent signed, as Python's repr and JavaScript print it.
        assert_eq!(Real(1.5e21).to_string(), "1.5e+21");
        assert_eq!(Real(f64::INFINITY).to_string(), "inf");
        for v in [15.0, 1e-300, -2.5e-7, 123456.789, f64::MAX, 5e-324, 1.0 / 3.0] {
            let text = Real(v).to_string();
            assert_eq!(text.parse::<f64>().map(f64::to_bits), Ok(v.to_bits()), "{text}");
            assert!(text.contains(['.', 'e']), "{text}");
        }
    }

    #[test]
    fn step_times_are_the_decimal_product_not_the_clocks_sum() {
        // The clock adds 0.001 684 times; the decimal 684 × 0.001 is 0.684.
        let summed = (0..684).fold(0.0, |t: f64, _| t + 0.001);
        assert_eq!(summed, 0.6840000000000005);
        let clock = StepClock::new(0.001);
        assert_eq!(clock.time_s(684), 0.684);
        assert_eq!(clock.time_s(0), 0.0);
        assert_eq!(StepClock::new(2.5e-4).time_s(3), 0.00075);
        assert_eq!(StepClock::new(1e-5).time_s(123_456_789), 1234.56789);
        // Δt's own digits: 0.1 + 0.2 has 17 of them, and so has its product.
        let odd = 0.1 + 0.2;
        assert_eq!(
            StepClock::new(odd).time_s(7),
            "2.10000000000000028".parse::<f64>().unwrap()
        );
        // A product past 2⁵³ is read from its decimal digits, still the nearest double.
        let big = StepClock::new(0.0012345678901234567);
        assert_eq!(
            big.time_s(10_000_000),
            "12345.678901234567".parse::<f64>().unwrap()
        );
        assert_eq!(StepClock::new(2.0).time_s(3), 6.0);
    }

    #[test]
    fn exact_numbers_read_back_and_take_an_exponent_only_at_the_extremes() {
        // A fit bound of 1e-200 printed as "0.000…0001", 202 characters.
        assert_eq!(fmt_exact(1e-200), "1e-200");
        assert_eq!(fmt_exact(-2.5e-7), "-2.5e-7");
        assert_eq!(fmt_exact(1e15), "1e15");
        assert_eq!(fmt_exact(20000.0), "20000");
        assert_eq!(fmt_exact(0.95), "0.95");
        assert_eq!(fmt_exact(0.1 + 0.2), "0.30000000000000004");
        assert_eq!(fmt_exact(0.0), "0");
        for v in [1e-200, 123456.789, 5e-324, f64::MAX, 1.0 / 3.0, -7e-7] {
            assert_eq!(fmt_exact(v).parse::<f64>(), Ok(v), "{v:e}");
            assert!(fmt_exact(v).len() <= 24, "{v:e}: {}", fmt_exact(v));
        }
    }

    #[test]
    fn tiny_p_values_keep_their_digits_and_plain_numbers_drop_trailing_zeros() {
        assert_eq!(fmt_num(6.0234e-28), "6.02e-28");
        assert_eq!(fmt_num(5.0e5), "500000");
        assert_eq!(fmt_num(2.5e6), "2.5e6");
        assert_eq!(fmt_num(0.0012), "0.0012");
        assert_eq!(fmt_num(0.5), "0.5");
        assert_eq!(fmt_num(0.0), "0");
        assert_eq!(fmt_num(f64::NAN), "NaN");
    }
}
