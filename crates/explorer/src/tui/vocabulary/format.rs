//! How numbers read on screen: one formatting for every panel.

use crate::tui::vocabulary::param::Param;

pub(crate) use dicesim_setup::number::fmt_num;

/// A value's allowed range as the list shows it, `min…max`.
pub(crate) fn fmt_range(p: Param) -> String {
    let l = p.limits();
    format!("{}…{}", fmt_num(l.min), fmt_num(l.max))
}

/// `12 345` (thin groups of three), as the batch size is written.
pub(crate) fn group(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(' ');
        }
        out.push(c);
    }
    out
}

/// A die's number as it is printed on it: the d%'s tens with two digits (`00`, `10` … `90`),
/// every other die's as it is (the d10's `0` … `9`).
pub(crate) fn face_text(kind: dicesim_physics::Solid, number: u32) -> String {
    if kind == dicesim_physics::Solid::Percentile {
        format!("{number:02}")
    } else {
        number.to_string()
    }
}
