//! Large type for the back row: a lesson step's sentence in letters five pixels high, drawn
//! with half blocks (`▀▄█`), so a letter is three terminal rows high and three columns wide
//! (the narrow ones one, `M` and `W` five): about three times the terminal's own type. Upper
//! case only (lower case is drawn upper), digits and the punctuation a sentence needs; a
//! lesson file's sentence is checked against [`missing`] when it is read.

/// Pixel rows of a glyph; [`ROWS`] terminal rows draw them (two pixels a row).
const PIXELS: usize = 5;
/// Terminal rows of one line of large type.
pub(crate) const ROWS: u16 = 3;
/// Terminal rows between two lines of large type.
pub(crate) const LEADING: u16 = 1;
/// Columns between two letters.
const GAP: usize = 1;
/// Columns of a space between words (besides the letters' gaps).
const SPACE: usize = 2;

/// Each character's pixels, `#` lit, every row of one glyph the same width.
const GLYPHS: &[(char, [&str; PIXELS])] = &[
    ('A', [".#.", "#.#", "###", "#.#", "#.#"]),
    ('B', ["##.", "#.#", "##.", "#.#", "##."]),
    ('C', [".##", "#..", "#..", "#..", ".##"]),
    ('D', ["##.", "#.#", "#.#", "#.#", "##."]),
    ('E', ["###", "#..", "##.", "#..", "###"]),
    ('F', ["###", "#..", "##.", "#..", "#.."]),
    ('G', [".##", "#..", "#.#", "#.#", ".##"]),
    ('H', ["#.#", "#.#", "###", "#.#", "#.#"]),
    ('I', ["#", "#", "#", "#", "#"]),
    ('J', ["..#", "..#", "..#", "#.#", ".#."]),
    ('K', ["#.#", "#.#", "##.", "#.#", "#.#"]),
    ('L', ["#..", "#..", "#..", "#..", "###"]),
    ('M', ["#...#", "##.##", "#.#.#", "#...#", "#...#"]),
    ('N', ["#..#", "##.#", "#.##", "#..#", "#..#"]),
    ('O', [".#.", "#.#", "#.#", "#.#", ".#."]),
    ('P', ["##.", "#.#", "##.", "#..", "#.."]),
    ('Q', [".#.", "#.#", "#.#", "##.", ".##"]),
    ('R', ["##.", "#.#", "##.", "#.#", "#.#"]),
    ('S', [".##", "#..", ".#.", "..#", "##."]),
    ('T', ["###", ".#.", ".#.", ".#.", ".#."]),
    ('U', ["#.#", "#.#", "#.#", "#.#", "###"]),
    ('V', ["#.#", "#.#", "#.#", "#.#", ".#."]),
    ('W', ["#...#", "#...#", "#.#.#", "##.##", "#...#"]),
    ('X', ["#.#", "#.#", ".#.", "#.#", "#.#"]),
    ('Y', ["#.#", "#.#", ".#.", ".#.", ".#."]),
    ('Z', ["###", "..#", ".#.", "#..", "###"]),
    ('0', ["###", "#.#", "#.#", "#.#", "###"]),
    ('1', [".#.", "##.", ".#.", ".#.", "###"]),
    ('2', ["##.", "..#", ".#.", "#..", "###"]),
    ('3', ["##.", "..#", ".#.", "..#", "##."]),
    ('4', ["#.#", "#.#", "###", "..#", "..#"]),
    ('5', ["###", "#..", "##.", "..#", "##."]),
    ('6', [".##", "#..", "###", "#.#", "###"]),
    ('7', ["###", "..#", ".#.", ".#.", ".#."]),
    ('8', ["###", "#.#", "###", "#.#", "###"]),
    ('9', ["###", "#.#", "###", "..#", "##."]),
    ('.', [".", ".", ".", ".", "#"]),
    (',', [".", ".", ".", "#", "#"]),
    (':', [".", "#", ".", "#", "."]),
    (';', [".", "#", ".", "#", "#"]),
    ('!', ["#", "#", "#", ".", "#"]),
    ('?', ["##.", "..#", ".#.", "...", ".#."]),
    ('\'', ["#", "#", ".", ".", "."]),
    ('"', ["#.#", "#.#", "...", "...", "..."]),
    ('-', ["...", "...", "###", "...", "..."]),
    ('+', ["...", ".#.", "###", ".#.", "..."]),
    ('=', ["...", "###", "...", "###", "..."]),
    ('×', ["...", "#.#", ".#.", "#.#", "..."]),
    ('/', ["..#", "..#", ".#.", "#..", "#.."]),
    ('%', ["#.#", "..#", ".#.", "#..", "#.#"]),
    ('(', [".#", "#.", "#.", "#.", ".#"]),
    (')', ["#.", ".#", ".#", ".#", "#."]),
    ('°', [".#.", "#.#", ".#.", "...", "..."]),
    ('·', [".", ".", "#", ".", "."]),
];

/// The glyph of `c`, lower case drawn as upper and typographic dashes and quotes as plain ones.
fn glyph(c: char) -> Option<&'static [&'static str; PIXELS]> {
    let c = match c {
        '–' | '—' | '−' => '-',
        '‘' | '’' => '\'',
        '“' | '”' => '"',
        c => c.to_uppercase().next().unwrap_or(c),
    };
    GLYPHS.iter().find(|(g, _)| *g == c).map(|(_, rows)| rows)
}

/// The characters of `text` that large type has no glyph for, each once, in order.
pub(crate) fn missing(text: &str) -> Vec<char> {
    let mut out = Vec::new();
    for c in text.chars().filter(|c| !c.is_whitespace()) {
        if glyph(c).is_none() && !out.contains(&c) {
            out.push(c);
        }
    }
    out
}

/// Columns `word` takes in large type (its letters and the gaps between them).
pub(crate) fn width(word: &str) -> usize {
    let letters: usize = word
        .chars()
        .map(|c| glyph(c).map_or(0, |g| g[0].chars().count()))
        .sum();
    letters + GAP * word.chars().count().saturating_sub(1)
}

/// `text`'s words in lines of at most `columns` columns of large type, never cutting a
/// word; `None` if a word alone is wider.
pub(crate) fn wrap(text: &str, columns: usize) -> Option<Vec<String>> {
    let mut lines: Vec<String> = Vec::new();
    let mut current = String::new();
    for word in text.split_whitespace() {
        if width(word) > columns {
            return None;
        }
        let joined = if current.is_empty() {
            word.to_string()
        } else {
            format!("{current} {word}")
        };
        if line_width(&joined) <= columns {
            current = joined;
        } else {
            lines.push(std::mem::replace(&mut current, word.to_string()));
        }
    }
    if !current.is_empty() {
        lines.push(current);
    }
    Some(lines)
}

/// Columns a line of words takes: the words, and between two words a space and two gaps.
fn line_width(line: &str) -> usize {
    let words: Vec<&str> = line.split(' ').collect();
    words.iter().map(|w| width(w)).sum::<usize>() + (SPACE + 2 * GAP) * words.len().saturating_sub(1)
}

/// Rows a text in `lines` lines of large type takes.
pub(crate) fn height(lines: usize) -> u16 {
    (lines as u16 * (ROWS + LEADING)).saturating_sub(LEADING)
}

/// One line of words in large type: [`ROWS`] strings of half blocks, [`line_width`] long.
pub(crate) fn render_line(line: &str) -> [String; ROWS as usize] {
    let mut pixels: [String; PIXELS] = Default::default();
    for (i, word) in line.split(' ').enumerate() {
        if i > 0 {
            for row in &mut pixels {
                row.push_str(&".".repeat(SPACE + 2 * GAP));
            }
        }
        for (j, c) in word.chars().enumerate() {
            let Some(g) = glyph(c) else { continue };
            for (row, pattern) in pixels.iter_mut().zip(g.iter()) {
                if j > 0 {
                    row.push_str(&".".repeat(GAP));
                }
                row.push_str(pattern);
            }
        }
    }
    let lit = |row: usize, x: usize| pixels.get(row).and_then(|r| r.as_bytes().get(x)) == Some(&b'#');
    let columns = pixels[0].len();
    std::array::from_fn(|r| {
        (0..columns)
            .map(|x| match (lit(2 * r, x), lit(2 * r + 1, x)) {
                (true, true) => '█',
                (true, false) => '▀',
                (false, true) => '▄',
                (false, false) => ' ',
            })
            .collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_glyph_has_rows_of_one_width_and_lines_are_as_wide_as_measured() {
        for (c, rows) in GLYPHS {
            let w = rows[0].chars().count();
            assert!(rows.iter().all(|r| r.chars().count() == w), "{c}");
        }
        // "HI": H 3, a gap, I 1.
        assert_eq!(width("HI"), 5);
        let drawn = render_line("HI a");
        assert!(drawn.iter().all(|r| r.chars().count() == line_width("HI a")));
        // The H's top two pixel rows are lit at both sides: full blocks.
        assert!(drawn[0].starts_with("█ █ █"), "{drawn:?}");
        // A 5-pixel glyph's last row is the top half of the third terminal row.
        assert_eq!(drawn[2].chars().next(), Some('▀'));
    }

    #[test]
    fn wrapping_never_cuts_a_word_and_refuses_one_too_wide() {
        let lines = wrap("the die is deterministic yet unpredictable", 60).expect("fits");
        assert!(lines.len() > 1);
        for l in &lines {
            assert!(line_width(l) <= 60, "{l}");
        }
        assert_eq!(lines.join(" "), "the die is deterministic yet unpredictable");
        assert_eq!(wrap("unpredictable", 10), None);
        assert_eq!(missing("spin ω > 0"), vec!['ω', '>']);
    }
}
