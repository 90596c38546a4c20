//! How numbers read on screen: one formatting for every panel.

use super::param::Param;

pub(crate) use crate::experiment::number::fmt_num;

/// A value's allowed range as the list shows it, `min…max`.
pub(crate) fn fmt_range(p: Param) -> String {
    let l = p.limits();
    format!("{}…{}", fmt_num(l.min), fmt_num(l.max))
}

/// `text` broken at spaces into lines of at most `width` characters (a longer word gets a
/// line of its own).
pub(crate) fn wrap_words(text: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let needed = line.chars().count() + usize::from(!line.is_empty()) + word.chars().count();
        if !line.is_empty() && needed > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
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
