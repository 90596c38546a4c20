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

/// A number exactly as given, for a value a person typed (a fit's bound, a range's end):
/// the shortest digits that read back as it, with an exponent where a person reads it
/// better (`1e-200`, not a 202-character decimal). The parameter errors' own formatting, so
/// a bound reads the same in a refusal and in a result.
pub use dicesim_physics::params::fmt_number as fmt_exact;

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
    use super::{fmt_exact, fmt_num};

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
