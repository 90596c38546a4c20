//! A player's own counts of a die's faces ("Is my die fair?", docs/real-dice.md): a small
//! CSV file of `face,count` rows, or the same pairs on the command line, checked against
//! the die the simulation rolls before anything is rolled.
//!
//! A file's `#` lines are notes for the reader, kept with the counts; three of them have a
//! meaning: `# die: d20` names the die the counts are of (held against the setup's die),
//! and `# surface: …` and `# throw: …` say how the player threw it (shown beside the
//! result: the simulation throws as its preset says).

use crate::Error;
use crate::compare_stats::MIN_EXPECTED;
use crate::stats::numbers_words;
use serde::Serialize;

/// Where in the input a row or a note is: a file's line, or an item of `--counts`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Place {
    /// The file's path, or `--counts` for counts given on the command line.
    pub origin: String,
    /// 1-based: the line of a file, the item of a list.
    pub index: usize,
    /// Whether the counts were given inline (`item`) or in a file (`line`).
    pub inline: bool,
}

/// E.g. `counts.csv, line 4` or `--counts, item 3`.
impl std::fmt::Display for Place {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let what = if self.inline { "item" } else { "line" };
        write!(f, "{}, {what} {}", self.origin, self.index)
    }
}

/// One counted face, where it was given.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Row {
    place: Place,
    face: u8,
    count: u64,
}

/// The counts as read, before they are held against a die.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CountsInput {
    origin: String,
    inline: bool,
    rows: Vec<Row>,
    /// The die the input names (`# die: d20`) and where.
    die: Option<(String, Place)>,
    /// The `#` lines naming the die, the surface and the throw, trimmed, in order.
    notes: Vec<String>,
    /// The place past the last row: where a refusal of the whole input points.
    end: Place,
}

/// A player's counts of one die, checked against it: one count per number the die shows,
/// in the die's order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlayerCounts {
    /// The file's path, or `--counts` for counts given on the command line.
    pub origin: String,
    /// The die's name as players say it (`d6` for the box, `d20`, `d%`).
    pub die: String,
    /// The numbers the die shows, in its order.
    pub numbers: Vec<u8>,
    /// Rolls counted showing each number.
    pub counts: Vec<u64>,
    /// The input's `#` lines naming the die, the surface and the throw, joined.
    pub notes: String,
}

impl PlayerCounts {
    pub fn total(&self) -> u64 {
        self.counts.iter().sum()
    }
}

/// The name players give a die of `kind` (its `die.kind`; `box`, whose numbers are the
/// paper's 1 to 6, is a d6).
pub fn player_die_name(kind: &str) -> String {
    if kind == "box" {
        "d6".to_string()
    } else {
        kind.to_string()
    }
}

/// The shipped preset that throws a die of this name from any orientation, for counts that
/// name their die and a run given no preset: the dice's own presets, and for a d6
/// `casino-die`, the paper's ideal cube at a real size thrown from any orientation.
pub fn preset_for_die(die: &str) -> Option<&'static str> {
    match die {
        "d4" => Some("d4"),
        "d6" => Some("casino-die"),
        "d8" => Some("d8"),
        "d10" => Some("d10"),
        "d%" => Some("d100"),
        "d12" => Some("d12"),
        "d20" => Some("d20"),
        _ => None,
    }
}

/// A count: a whole number, not negative.
fn parse_count(text: &str, place: &Place) -> Result<u64, Error> {
    let refuse = |why: String| Err(Error::Compare(format!("{place}: {why}")));
    let text = text.trim();
    if let Ok(n) = text.parse::<u64>() {
        return Ok(n);
    }
    match text.parse::<f64>() {
        Ok(x) if x < 0.0 => refuse(format!(
            "the count `{text}` is negative: a count is how many rolls showed the face, 0 or more"
        )),
        Ok(_) => refuse(format!(
            "the count `{text}` is not a whole number: a count is how many rolls showed the face"
        )),
        Err(_) => refuse(format!("the count `{text}` is not a number")),
    }
}

/// A face: the number printed on it.
fn parse_face(text: &str, place: &Place) -> Result<u8, Error> {
    let text = text.trim();
    text.parse::<u8>().map_err(|_| {
        Error::Compare(format!(
            "{place}: `{text}` is not a face's number (a whole number as printed on the die, e.g. 20)"
        ))
    })
}

impl CountsInput {
    /// `--counts`'s value: `FACE=COUNT` pairs when it holds a `=`, else a file's path, read
    /// and checked (each refusal names its line or item) before anything is rolled.
    pub fn read(argument: &str) -> Result<CountsInput, Error> {
        if argument.contains('=') {
            return CountsInput::from_inline(argument);
        }
        let text = std::fs::read_to_string(argument)
            .map_err(|e| Error::Compare(format!("cannot read the counts file `{argument}`: {e}")))?;
        CountsInput::from_file_text(&text, argument)
    }

    /// A counts file: `#` lines, an optional `face,count` header, then one `face,count` row
    /// per face. `origin` names it in every refusal.
    pub fn from_file_text(text: &str, origin: &str) -> Result<CountsInput, Error> {
        let mut input = CountsInput::empty(origin, false);
        let mut header_allowed = true;
        let mut lines = 0;
        for (i, line) in text.lines().enumerate() {
            lines = i + 1;
            let place = input.place(i + 1);
            let line = line.trim();
            if let Some(note) = line.strip_prefix('#') {
                input.note(note.trim(), place)?;
                continue;
            }
            if line.is_empty() {
                continue;
            }
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            if header_allowed && cells == ["face", "count"] {
                header_allowed = false;
                continue;
            }
            header_allowed = false;
            let [face, count] = cells[..] else {
                return Err(Error::Compare(format!(
                    "{place}: `{line}` is not a row `face,count` (e.g. `20,7`)"
                )));
            };
            input.row(face, count, place)?;
        }
        input.end = input.place(lines.max(1));
        Ok(input)
    }

    /// Counts on the command line: `FACE=COUNT` pairs separated by commas, e.g.
    /// `1=12,2=9,3=11`; each pair is an item, numbered from 1 in refusals.
    pub fn from_inline(text: &str) -> Result<CountsInput, Error> {
        let mut input = CountsInput::empty("--counts", true);
        let items: Vec<&str> = text.split(',').collect();
        for (i, item) in items.iter().enumerate() {
            let place = input.place(i + 1);
            let item = item.trim();
            if item.is_empty() && items.len() == 1 {
                break;
            }
            let Some((face, count)) = item.split_once('=') else {
                return Err(Error::Compare(format!(
                    "{place}: `{item}` is not FACE=COUNT (e.g. `20=7`)"
                )));
            };
            input.row(face, count, place)?;
        }
        input.end = input.place(items.len().max(1));
        Ok(input)
    }

    fn empty(origin: &str, inline: bool) -> CountsInput {
        CountsInput {
            origin: origin.to_string(),
            inline,
            rows: Vec::new(),
            die: None,
            notes: Vec::new(),
            end: Place {
                origin: origin.to_string(),
                index: 1,
                inline,
            },
        }
    }

    fn place(&self, index: usize) -> Place {
        Place {
            origin: self.origin.clone(),
            index,
            inline: self.inline,
        }
    }

    /// A `#` line: kept as a note; `die: NAME` also names the die (once).
    fn note(&mut self, note: &str, place: Place) -> Result<(), Error> {
        if let Some(name) = note.strip_prefix("die:") {
            let name = name.trim().to_string();
            if let Some((_, first)) = &self.die {
                return Err(Error::Compare(format!(
                    "{place}: the die is named twice (first at line {})",
                    first.index
                )));
            }
            self.die = Some((name, place));
        }
        // The notes with a meaning travel with the counts; the rest are the file's comments.
        if ["die:", "surface:", "throw:"].iter().any(|k| note.starts_with(k)) {
            self.notes.push(note.to_string());
        }
        Ok(())
    }

    fn row(&mut self, face: &str, count: &str, place: Place) -> Result<(), Error> {
        let face = parse_face(face, &place)?;
        let count = parse_count(count, &place)?;
        if let Some(first) = self.rows.iter().find(|r| r.face == face) {
            return Err(Error::Compare(format!(
                "{place}: face {face} is counted twice (first at {} {})",
                if self.inline { "item" } else { "line" },
                first.place.index
            )));
        }
        self.rows.push(Row { place, face, count });
        Ok(())
    }

    /// The die the input names (`# die: d20`), if any.
    pub fn named_die(&self) -> Option<&str> {
        self.die.as_ref().map(|(name, _)| name.as_str())
    }

    /// The counts held against the die the simulation rolls, `die` as players name it
    /// ([`player_die_name`]) showing `numbers`: refused, naming the line, for a die named
    /// otherwise, a face the die does not show, a face left out, no counts at all, and
    /// fewer than 5 rolls expected per face (the χ² test's rule).
    pub fn for_die(self, die: &str, numbers: &[u8]) -> Result<PlayerCounts, Error> {
        let refuse = |place: &Place, why: String| Err(Error::Compare(format!("{place}: {why}")));
        let shows = format!("a {die} shows {}", numbers_words(numbers));
        if let Some((named, place)) = &self.die
            && named != die
        {
            return refuse(
                place,
                format!(
                    "the counts are of a {named}, but the die rolled is a {die} (choose its preset with \
                     --preset, or name the die the counts are of)"
                ),
            );
        }
        if self.rows.is_empty() {
            return refuse(
                &self.end,
                "no counts: give one row `face,count` per face of the die".to_string(),
            );
        }
        if let Some(row) = self.rows.iter().find(|r| !numbers.contains(&r.face)) {
            return refuse(
                &row.place,
                format!("face {}: {shows}, so these are not counts of it", row.face),
            );
        }
        let last = &self.rows[self.rows.len() - 1].place;
        let missing: Vec<u8> = numbers
            .iter()
            .copied()
            .filter(|n| !self.rows.iter().any(|r| r.face == *n))
            .collect();
        if !missing.is_empty() {
            return refuse(
                last,
                format!(
                    "{} faces counted, but {shows} ({} numbers): {} missing (count a face never rolled as 0)",
                    self.rows.len(),
                    numbers.len(),
                    numbers_words(&missing)
                ),
            );
        }
        let counts: Vec<u64> = numbers
            .iter()
            .map(|n| self.rows.iter().find(|r| r.face == *n).map_or(0, |r| r.count))
            .collect();
        let total: u64 = counts.iter().sum();
        let expected = total as f64 / numbers.len() as f64;
        if expected < MIN_EXPECTED {
            let needed = (MIN_EXPECTED * numbers.len() as f64).ceil() as u64;
            return refuse(
                last,
                format!(
                    "{total} rolls of a {die} expect {} per face; the χ² test needs at least {} per \
                     face: roll at least {needed} times",
                    fmt_expected(expected),
                    MIN_EXPECTED
                ),
            );
        }
        Ok(PlayerCounts {
            origin: self.origin,
            die: die.to_string(),
            numbers: numbers.to_vec(),
            counts,
            notes: self.notes.join("; "),
        })
    }
}

/// An expected count in words: `3`, `4.5`.
fn fmt_expected(x: f64) -> String {
    let s = format!("{x:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    const D6: &[u8] = &[1, 2, 3, 4, 5, 6];
    const D20: &[u8] = &[
        1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,
    ];

    fn d20_file(rows: &[(u8, &str)]) -> String {
        let mut text = "# die: d20\n# surface: a felt tray\n# bought in 2024\nface,count\n".to_string();
        for (face, count) in rows {
            text.push_str(&format!("{face},{count}\n"));
        }
        text
    }

    fn refusal(text: &str, die: &str, numbers: &[u8]) -> String {
        CountsInput::from_file_text(text, "my.csv")
            .and_then(|i| i.for_die(die, numbers))
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn a_file_of_counts_reads_in_the_dies_order_with_its_notes() {
        let rows: Vec<(u8, String)> = (1..=20).rev().map(|f| (f, (f as u64 + 10).to_string())).collect();
        let rows: Vec<(u8, &str)> = rows.iter().map(|(f, c)| (*f, c.as_str())).collect();
        let input = CountsInput::from_file_text(&d20_file(&rows), "my.csv").unwrap();
        assert_eq!(input.named_die(), Some("d20"));
        let counts = input.for_die("d20", D20).unwrap();
        // Given 20 first, read back in the die's order: face f counted f + 10 times.
        assert_eq!(counts.counts, (11..=30).collect::<Vec<u64>>());
        assert_eq!(counts.total(), (11..=30).sum::<u64>());
        assert_eq!(counts.notes, "die: d20; surface: a felt tray");
        let inline = CountsInput::from_inline("1=10, 2=11,3=12,4=13,5=14,6=15")
            .unwrap()
            .for_die("d6", D6)
            .unwrap();
        assert_eq!(inline.counts, [10, 11, 12, 13, 14, 15]);
        assert_eq!(inline.origin, "--counts");
    }

    #[test]
    fn bad_counts_are_refused_naming_the_line() {
        let fine: Vec<(u8, &str)> = (1..=20).map(|f| (f, "6")).collect();
        // Lines: 1–4 the notes and header, faces from line 5.
        let mut unknown = fine.clone();
        unknown[19] = (21, "6");
        let e = refusal(&d20_file(&unknown), "d20", D20);
        assert_eq!(
            e,
            "my.csv, line 24: face 21: a d20 shows 1–20, so these are not counts of it"
        );
        let mut negative = fine.clone();
        negative[4] = (5, "-3");
        let e = refusal(&d20_file(&negative), "d20", D20);
        assert!(e.starts_with("my.csv, line 9: the count `-3` is negative"), "{e}");
        let mut fraction = fine.clone();
        fraction[0] = (1, "2.5");
        let e = refusal(&d20_file(&fraction), "d20", D20);
        assert!(
            e.starts_with("my.csv, line 5: the count `2.5` is not a whole number"),
            "{e}"
        );
        // 20 faces of 4 rolls: 80 rolls expect 4 per face.
        let few: Vec<(u8, &str)> = (1..=20).map(|f| (f, "4")).collect();
        let e = refusal(&d20_file(&few), "d20", D20);
        assert_eq!(
            e,
            "my.csv, line 24: 80 rolls of a d20 expect 4 per face; the χ² test needs at least 5 per face: roll at least 100 times"
        );
        // Six counts for a d20 (a d6's file held against the d20), and the die named.
        let six = "face,count\n1,10\n2,10\n3,10\n4,10\n5,10\n6,10\n";
        let e = refusal(six, "d20", D20);
        assert_eq!(
            e,
            "my.csv, line 7: 6 faces counted, but a d20 shows 1–20 (20 numbers): 7–20 missing (count a face never rolled as 0)"
        );
        let e = refusal(&format!("# die: d6\n{six}"), "d20", D20);
        assert!(
            e.starts_with("my.csv, line 1: the counts are of a d6, but the die rolled is a d20"),
            "{e}"
        );
        let e = refusal("# my die\n\n", "d20", D20);
        assert_eq!(
            e,
            "my.csv, line 2: no counts: give one row `face,count` per face of the die"
        );
        let e = refusal("", "d20", D20);
        assert_eq!(
            e,
            "my.csv, line 1: no counts: give one row `face,count` per face of the die"
        );
        let e = refusal("face,count\n1,6\n1,7\n", "d20", D20);
        assert_eq!(e, "my.csv, line 3: face 1 is counted twice (first at line 2)");
        let e = refusal("face,count\none,6\n", "d20", D20);
        assert!(
            e.starts_with("my.csv, line 2: `one` is not a face's number"),
            "{e}"
        );
        let e = refusal("face,count\n1;6\n", "d20", D20);
        assert!(
            e.starts_with("my.csv, line 2: `1;6` is not a row `face,count`"),
            "{e}"
        );
        let e = CountsInput::from_inline("1=10,2=x").unwrap_err().to_string();
        assert_eq!(e, "--counts, item 2: the count `x` is not a number");
        let e = CountsInput::from_inline("1=10,2:4").unwrap_err().to_string();
        assert!(e.starts_with("--counts, item 2: `2:4` is not FACE=COUNT"), "{e}");
    }
}
