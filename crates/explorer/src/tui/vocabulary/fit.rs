//! How text fits a panel, one rule for every panel: its parts and lines are ranked by
//! importance (0 matters most), and what does not fit is dropped from the least important
//! up; a text still too wide wraps at spaces, or where it has one line, is cut at a word's
//! end and marked `…`. A word is never cut mid-way at an edge, and a panel's text stops one
//! column short of its right edge, so a class never reads a cut word as a whole one.

use ratatui::style::Style;
use ratatui::text::{Line, Span};

/// Columns a panel's text leaves free at its right edge.
pub(crate) const GAP: usize = 1;

/// Characters of text a panel `width` columns wide (inside its border) holds on a line.
pub(crate) fn room(width: usize) -> usize {
    width.saturating_sub(GAP)
}

/// Items ranked by importance, dropped from the least important (the highest rank; among
/// equals the last) until `fits` says the rest fit; the rest keep their order.
pub(crate) fn by_rank<T>(mut items: Vec<(u8, T)>, fits: impl Fn(&[&T]) -> bool) -> Vec<T> {
    loop {
        let kept: Vec<&T> = items.iter().map(|(_, t)| t).collect();
        if fits(&kept) || items.is_empty() {
            break;
        }
        let least = (0..items.len())
            .max_by_key(|&i| (items[i].0, i))
            .expect("not empty");
        items.remove(least);
    }
    items.into_iter().map(|(_, t)| t).collect()
}

/// Lines ranked by importance, as many as `height` rows hold, in their order.
pub(crate) fn rows<T>(lines: Vec<(u8, T)>, height: usize) -> Vec<T> {
    by_rank(lines, |kept| kept.len() <= height)
}

/// The parts of one line, ranked, as many as fit `width` (a panel's inside): the least
/// important go first, and if the most important alone are too wide, they are cut at a
/// word's end with `…`.
pub(crate) fn line(parts: Vec<(u8, Vec<Span<'static>>)>, width: usize) -> Line<'static> {
    let kept = by_rank(parts, |kept| {
        kept.len() <= 1 || kept.iter().map(|p| spans_width(p)).sum::<usize>() <= room(width)
    });
    abbreviate(Line::from(kept.concat()), width)
}

fn spans_width(spans: &[Span]) -> usize {
    spans.iter().map(|s| s.content.chars().count()).sum()
}

/// The first of `forms` (the same words, longest first) that fits `width`, or the last one
/// cut at a word's end.
pub(crate) fn longest_fitting(forms: &[String], width: usize) -> String {
    forms
        .iter()
        .find(|f| f.chars().count() <= room(width))
        .cloned()
        .unwrap_or_else(|| cut_text(forms.last().map_or("", String::as_str), room(width)))
}

/// `line` as it is if it fits `width`, else cut after its last whole word that leaves room
/// for `…` (trailing spaces and separators dropped before the mark).
pub(crate) fn abbreviate(line: Line<'static>, width: usize) -> Line<'static> {
    let limit = room(width);
    if line.width() <= limit {
        return line;
    }
    let text: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
    let keep = cut_text(&text, limit).chars().count();
    // Rebuild the spans up to `keep` characters, then the mark in the last kept style.
    let mut out = Vec::new();
    let mut left = keep.saturating_sub(1);
    for span in line.spans {
        if left == 0 {
            break;
        }
        let n = span.content.chars().count().min(left);
        let content: String = span.content.chars().take(n).collect();
        left -= n;
        out.push(Span::styled(content, span.style));
    }
    let style = out.last().map(|s: &Span| s.style).unwrap_or_default();
    out.push(Span::styled("…", style));
    Line::from(out).style(line.style)
}

/// `text` cut to at most `limit` characters at a word's end, with `…` (a single word longer
/// than the limit is cut where it must be, still marked).
pub(crate) fn cut_text(text: &str, limit: usize) -> String {
    if text.chars().count() <= limit {
        return text.to_string();
    }
    if limit == 0 {
        return String::new();
    }
    let chars: Vec<char> = text.chars().collect();
    let head = &chars[..limit - 1];
    // The last space before which the text ends a word.
    let end = head
        .iter()
        .rposition(|c| *c == ' ')
        .filter(|&i| head[..i].iter().any(|c| !c.is_whitespace()))
        .unwrap_or(head.len());
    let kept: String = head[..end].iter().collect();
    let kept = kept.trim_end_matches([' ', '·', ',', ';', ':', '(']);
    format!("{kept}…")
}

/// `text` broken at spaces into lines that fit `width` (a panel's inside); a word longer
/// than a line is cut, marked `…`.
pub(crate) fn wrap(text: &str, width: usize) -> Vec<String> {
    let limit = room(width).max(1);
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let needed = line.chars().count() + usize::from(!line.is_empty()) + word.chars().count();
        if !line.is_empty() && needed > limit {
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
    lines.into_iter().map(|l| cut_text(&l, limit)).collect()
}

/// `lines` wrapped to fit `width` with a hanging indent: a line too wide breaks after its
/// last ` · ` that fits (the parts of a line are its natural units), else at its last space,
/// and goes on indented two columns past its own indent, so a wrapped value reads as part of
/// its line, not as a line of its own. Styles are kept character by character.
pub(crate) fn hanging(lines: Vec<Line<'static>>, width: usize) -> Vec<Line<'static>> {
    let limit = room(width).max(1);
    let mut out = Vec::new();
    for line in lines {
        let cells: Vec<(char, Style)> = line
            .spans
            .iter()
            .flat_map(|s| s.content.chars().map(move |c| (c, line.style.patch(s.style))))
            .collect();
        if cells.len() <= limit {
            out.push(line);
            continue;
        }
        let indent = cells.iter().take_while(|(c, _)| *c == ' ').count();
        let lead = " ".repeat((indent + 2).min(limit / 2));
        let mut rest: &[(char, Style)] = &cells;
        let mut first = true;
        while !rest.is_empty() {
            let prefix = if first { 0 } else { lead.chars().count() };
            let room_here = limit.saturating_sub(prefix).max(1);
            let (piece, next) = if rest.len() <= room_here {
                (rest, &rest[rest.len()..])
            } else {
                let at = |i: usize| rest[i].0;
                let separator = (1..room_here.saturating_sub(1))
                    .rev()
                    .find(|&i| at(i) == '·' && at(i - 1) == ' ' && at(i + 1) == ' ');
                let space = (1..=room_here).rev().find(|&i| at(i) == ' ');
                match (separator, space) {
                    // The line ends before the separator; the next part starts after it.
                    (Some(i), _) if i > indent + 1 => (&rest[..i - 1], &rest[i + 2..]),
                    (_, Some(i)) if i > indent => (&rest[..i], &rest[i + 1..]),
                    // No space to break at: the word is cut and marked (below).
                    _ => (&rest[..room_here - 1], &rest[rest.len()..]),
                }
            };
            let mut spans = Vec::new();
            if !first {
                spans.push(Span::raw(lead.clone()));
            }
            spans.extend(styled_runs(piece));
            if piece.len() < rest.len() && next.is_empty() {
                spans.push(Span::raw("…"));
            }
            out.push(Line::from(spans));
            rest = next;
            first = false;
        }
    }
    out
}

/// Consecutive characters of one style as one span.
fn styled_runs(cells: &[(char, Style)]) -> Vec<Span<'static>> {
    let mut spans: Vec<Span<'static>> = Vec::new();
    let mut text = String::new();
    let mut style = cells.first().map_or(Style::new(), |c| c.1);
    for &(c, s) in cells {
        if s != style && !text.is_empty() {
            spans.push(Span::styled(std::mem::take(&mut text), style));
        }
        style = s;
        text.push(c);
    }
    if !text.is_empty() {
        spans.push(Span::styled(text, style));
    }
    spans
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plain(line: &Line) -> String {
        line.spans.iter().map(|s| s.content.as_ref()).collect()
    }

    #[test]
    fn the_least_important_part_goes_first() {
        let parts = vec![
            (0, vec![Span::raw(" die")]),
            (2, vec![Span::raw(" · lowest corner -0.07 cm")]),
            (0, vec![Span::raw(" · face up 3 ")]),
        ];
        // 4 + 13 = 17 characters of the two parts that matter, and the gap column.
        assert_eq!(plain(&line(parts.clone(), 18)), " die · face up 3 ");
        assert_eq!(
            plain(&line(parts, 60)),
            " die · lowest corner -0.07 cm · face up 3 "
        );
    }

    #[test]
    fn a_line_too_wide_ends_at_a_words_end_with_an_ellipsis() {
        // The cut hint, `initial.height 0…1000 · restarts th`.
        let cut = cut_text("initial.height 0…1000 · restarts the roll", 34);
        assert_eq!(cut, "initial.height 0…1000 · restarts…");
        assert_eq!(cut_text("abcdefgh", 5), "abcd…");
        assert_eq!(cut_text("fits", 4), "fits");
        let l = abbreviate(Line::from(vec![Span::raw("F 980 "), Span::raw("(M·g/8)")]), 11);
        assert_eq!(plain(&l), "F 980…");
    }

    #[test]
    fn rows_drop_from_the_least_important_up_and_keep_their_order() {
        let lines = vec![
            (1, "heading"),
            (0, "face 1"),
            (3, "last rolls"),
            (0, "face 2"),
            (2, "p"),
        ];
        assert_eq!(rows(lines.clone(), 3), vec!["heading", "face 1", "face 2"]);
        assert_eq!(rows(lines, 2), vec!["face 1", "face 2"]);
    }

    #[test]
    fn wrapped_lines_leave_the_gap_column() {
        let lines = wrap("0.1: corner in the table; ≥ 1.529 cm keeps it above", 21);
        assert_eq!(
            lines,
            vec!["0.1: corner in the", "table; ≥ 1.529 cm", "keeps it above"]
        );
        assert!(lines.iter().all(|l| l.chars().count() <= 20));
    }

    #[test]
    fn a_long_line_hangs_after_its_last_separator_that_fits() {
        let lines = vec![
            Line::raw("   spin ωx 1.091 · spin ωy 1.224"),
            Line::raw("   yaw pitch roll (20, 25, -15)°"),
            Line::raw(" short"),
        ];
        let out: Vec<String> = hanging(lines, 30).iter().map(plain).collect();
        assert_eq!(
            out,
            [
                "   spin ωx 1.091",
                "     spin ωy 1.224",
                "   yaw pitch roll (20, 25,",
                "     -15)°",
                " short",
            ]
        );
        // Every line leaves the gap column free.
        assert!(out.iter().all(|l| l.chars().count() <= room(30)));
        // A word longer than the line is cut and marked.
        let out: Vec<String> = hanging(vec![Line::raw("abcdefghij")], 6)
            .iter()
            .map(plain)
            .collect();
        assert_eq!(out, ["abcd…"]);
    }
}
