//! Putting the CSV parts of a sharded sweep back together: rows copied byte for byte in
//! shard order (so the merged file is the one-machine file), each part checked to hold
//! exactly the ids or cells its summary says, and a map's cells read back for its image.

use crate::basin::Cell;
use crate::columns::RecordCheck;
use dicesim_physics::{Outcome, Status};
use dicesim_setup::number::Real;
use std::io::{BufRead, Write};

/// Why a part's rows cannot be merged.
#[derive(Debug, thiserror::Error)]
pub(super) enum RowError {
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// The part's content disagrees with its summary (1-based line).
    #[error("line {line}: {message}")]
    Row { line: u64, message: String },
}

/// The longest line a records file of this program holds, bytes (a row is under 400, a
/// provenance line a few kB): a longer one is damage, refused before it fills memory.
pub(super) const MAX_LINE_BYTES: u64 = 64 * 1024;

/// Reads one line of at most [`MAX_LINE_BYTES`] without its line end; `None` at the end.
/// A last line without its line end is a file cut short.
pub(super) fn bounded_line(reader: &mut impl BufRead, buf: &mut Vec<u8>) -> Result<Option<String>, String> {
    buf.clear();
    let n = std::io::Read::take(&mut *reader, MAX_LINE_BYTES + 1)
        .read_until(b'\n', buf)
        .map_err(|e| e.to_string())?;
    if n == 0 {
        return Ok(None);
    }
    if buf.last() != Some(&b'\n') {
        return Err(if n as u64 > MAX_LINE_BYTES {
            format!("a line longer than {MAX_LINE_BYTES} bytes")
        } else {
            "the last line is cut short (no line end)".to_string()
        });
    }
    buf.pop();
    String::from_utf8(std::mem::take(buf))
        .map(Some)
        .map_err(|_| "a line that is not UTF-8 text".to_string())
}

/// The first line of a file without the UTF-8 byte-order mark a spreadsheet puts in front:
/// the mark is invisible, so a header refused for it would read the same as the one expected.
pub(super) fn without_bom(line: String) -> String {
    match line.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_string(),
        None => line,
    }
}

/// Copies the rows of one CSV part from `reader` to `out`, after checking that its first
/// lines are `leading` (the header; a byte-order mark in front is not part of it) and that row `n` (0-based, after them) passes `check(n, row)`; the part
/// must hold exactly `rows` rows. The leading lines themselves are not copied.
pub(super) fn copy_rows(
    mut reader: impl BufRead,
    out: &mut (impl Write + ?Sized),
    leading: &[&str],
    rows: u64,
    check: &mut dyn FnMut(u64, &str) -> Result<(), String>,
) -> Result<(), RowError> {
    let mut buf = Vec::new();
    let bad = |line: u64, message: String| RowError::Row { line, message };
    for (k, want) in leading.iter().enumerate() {
        let line = k as u64 + 1;
        let got = bounded_line(&mut reader, &mut buf).map_err(|e| bad(line, e))?;
        match got.map(|g| if k == 0 { without_bom(g) } else { g }) {
            Some(h) if h == *want => {}
            Some(h) => {
                let what = if k + 1 == leading.len() { "header" } else { "line" };
                return Err(bad(
                    line,
                    format!("{what} `{}`, expected `{want}`", h.escape_debug()),
                ));
            }
            None if k == 0 => return Err(bad(line, "empty file, expected a header".to_string())),
            None => return Err(bad(line, "the file ends before its rows".to_string())),
        }
    }
    let first = leading.len() as u64 + 1;
    let mut n = 0;
    while let Some(line) = bounded_line(&mut reader, &mut buf).map_err(|e| bad(first + n, e))? {
        if n == rows {
            return Err(bad(
                first + n,
                format!("more rows than the {rows} the part summary counts"),
            ));
        }
        check(n, &line).map_err(|m| bad(first + n, m))?;
        writeln!(out, "{line}")?;
        n += 1;
    }
    if n < rows {
        return Err(bad(
            first + n,
            format!("the file ends after {n} of the {rows} rows the part summary counts"),
        ));
    }
    Ok(())
}

/// Reads a map row (`i,j,x,y,start_face,face,status,steps,time_s,sampled`, as
/// [`BasinMap::write_csv`](crate::BasinMap::write_csv) writes it) that must be node
/// `(i, j)`; its floats are in shortest round-trip form, so the cell comes back exactly.
///
/// Its faces must be numbers the setup's die shows (`check`). With `node`, the cell's
/// coordinates as the map writes them (`x`, `y`), every field is checked: the coordinates
/// are the node's, the outcome one a roll can end in ([`RecordCheck::check_outcome`]), and
/// every cell written as the map writes it.
pub(super) fn parse_map_row(
    row: &str,
    i: usize,
    j: usize,
    check: &RecordCheck,
    node: Option<(&str, &str)>,
) -> Result<Cell, String> {
    let cells: Vec<&str> = row.split(',').collect();
    let [ri, rj, x, y, start_face, face, status, steps, time_s, sampled] = cells[..] else {
        return Err(format!("{} cells, expected 10", cells.len()));
    };
    if (ri.parse(), rj.parse()) != (Ok(i), Ok(j)) || (ri, rj) != (&i.to_string()[..], &j.to_string()[..]) {
        return Err(format!("cell ({ri}, {rj}), expected ({i}, {j})"));
    }
    if let Some((nx, ny)) = node
        && (x, y) != (nx, ny)
    {
        return Err(format!(
            "cell ({i}, {j}) at ({}, {}), but the map's axes put it at ({nx}, {ny})",
            x.escape_debug(),
            y.escape_debug()
        ));
    }
    let number = |what: &str, s: &str| format!("{what} `{s}` is not valid");
    // A number of the die's, or its refusal naming the column.
    let die_face = |what: &str, s: &str| match s.parse::<u8>() {
        Ok(f) if check.is_face(f) => Ok(f),
        Ok(f) => Err(check.not_a_face(what, f)),
        Err(_) => Err(number(what, s)),
    };
    let face = match face {
        "" => None,
        f => Some(die_face("face", f)?),
    };
    let status = Status::from_name(status).ok_or_else(|| number("status", status))?;
    let outcome = Outcome {
        status,
        face,
        steps: steps.parse().map_err(|_| number("steps", steps))?,
        time_s: time_s.parse().map_err(|_| number("time_s", time_s))?,
        // A map's file keeps each cell's ending, not its impacts (batch records do).
        impacts: 0,
        first_impact: None,
    };
    if node.is_some() {
        check.check_outcome(&outcome)?;
        let written = [outcome.steps.to_string(), Real(outcome.time_s).to_string()];
        if [steps, time_s] != [written[0].as_str(), written[1].as_str()] {
            return Err(format!(
                "`{steps}` steps, `{time_s}` s: not written as this program writes them"
            ));
        }
    }
    Ok(Cell {
        outcome,
        start_face: die_face("start_face", start_face)?,
        sampled: match sampled {
            "1" => true,
            "0" => false,
            s => return Err(number("sampled", s)),
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn copy(text: &str, rows: u64) -> Result<String, String> {
        let mut out = Vec::new();
        copy_rows(text.as_bytes(), &mut out, &["id,x"], rows, &mut |n, row| {
            let id = row.split(',').next().unwrap_or_default();
            match id.parse() == Ok(10 + n) {
                true => Ok(()),
                false => Err(format!("roll id `{id}`, expected {}", 10 + n)),
            }
        })
        .map_err(|e| e.to_string())?;
        Ok(String::from_utf8(out).unwrap())
    }

    #[test]
    fn rows_are_copied_after_their_checks() {
        assert_eq!(copy("id,x\n10,a\n11,b\n", 2).unwrap(), "10,a\n11,b\n");
        // A spreadsheet's byte-order mark in front of the header is not part of the header.
        assert_eq!(copy("\u{feff}id,x\n10,a\n", 1).unwrap(), "10,a\n");
        // Only in front: a mark anywhere else is a changed header, and named as one.
        assert_eq!(
            copy("id\u{feff},x\n10,a\n", 1).unwrap_err(),
            "line 1: header `id\\u{feff},x`, expected `id,x`"
        );
        assert_eq!(
            copy("id,y\n10,a\n", 1).unwrap_err(),
            "line 1: header `id,y`, expected `id,x`"
        );
        assert_eq!(
            copy("id,x\n10,a\n12,b\n", 2).unwrap_err(),
            "line 3: roll id `12`, expected 11"
        );
        assert_eq!(
            copy("id,x\n10,a\n", 2).unwrap_err(),
            "line 3: the file ends after 1 of the 2 rows the part summary counts"
        );
        assert_eq!(
            copy("id,x\n10,a\n11,b\n", 1).unwrap_err(),
            "line 3: more rows than the 1 the part summary counts"
        );
        assert_eq!(copy("", 0).unwrap_err(), "line 1: empty file, expected a header");
    }

    #[test]
    fn map_rows_read_back_exactly() {
        let check = RecordCheck::new(&dicesim_physics::Params::default());
        let parse_map_row = |row, i, j, node| parse_map_row(row, i, j, &check, node);
        let c = parse_map_row("3,1,-60.0,0.1,2,5,settled,1234,1.2345000000000002,1", 3, 1, None).unwrap();
        assert_eq!(c.outcome.face, Some(5));
        assert_eq!(c.outcome.status, Status::Settled);
        assert_eq!(c.outcome.steps, 1234);
        assert_eq!(c.outcome.time_s, 1.2345000000000002);
        assert_eq!((c.start_face, c.sampled), (2, true));
        let t = parse_map_row("0,0,1,1,6,,timeout,9,3,0", 0, 0, None).unwrap();
        assert_eq!(
            (t.outcome.face, t.outcome.status, t.sampled),
            (None, Status::Timeout, false)
        );
        assert_eq!(
            parse_map_row("0,0,1,1,6,,timeout,9,3,0", 1, 0, None).unwrap_err(),
            "cell (0, 0), expected (1, 0)"
        );
        assert_eq!(
            parse_map_row("0,0,1,1,6,7,settled,9,3,0", 0, 0, None).unwrap_err(),
            "face 7 is not a face of this die (its faces read 1–6)"
        );
        assert_eq!(
            parse_map_row("0,0,1,1,0,2,settled,9,3,0", 0, 0, None).unwrap_err(),
            "start_face 0 is not a face of this die (its faces read 1–6)"
        );
        assert_eq!(
            parse_map_row("0,0,1,1,6,x,settled,9,3,0", 0, 0, None).unwrap_err(),
            "face `x` is not valid"
        );
        assert_eq!(
            parse_map_row("0,0,1", 0, 0, None).unwrap_err(),
            "3 cells, expected 10"
        );
    }
}
