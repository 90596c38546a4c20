//! Putting the CSV parts of a sharded sweep back together: rows copied byte for byte in
//! shard order (so the merged file is the one-machine file), each part checked to hold
//! exactly the ids or cells its summary says, and a map's cells read back for its image.

use super::basin::Cell;
use crate::physics::{Outcome, Status};
use std::io::{BufRead, Write};

/// Why a part's rows cannot be merged.
#[derive(Debug, thiserror::Error)]
pub(crate) enum MergeError {
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// The part's content disagrees with its summary (1-based line).
    #[error("line {line}: {message}")]
    Row { line: u64, message: String },
}

/// Copies the rows of one CSV part from `reader` to `out`, after checking that its header
/// is `header` and that row `n` (0-based, after the header) passes `check(n, row)`; the
/// part must hold exactly `rows` rows. The header itself is not copied.
pub(crate) fn copy_rows(
    reader: impl BufRead,
    out: &mut (impl Write + ?Sized),
    header: &str,
    rows: u64,
    check: &mut dyn FnMut(u64, &str) -> Result<(), String>,
) -> Result<(), MergeError> {
    let mut lines = reader.lines();
    let bad = |line: u64, message: String| MergeError::Row { line, message };
    match lines.next().transpose()? {
        Some(h) if h == header => {}
        Some(h) => return Err(bad(1, format!("header `{h}`, expected `{header}`"))),
        None => return Err(bad(1, "empty file, expected a header".to_string())),
    }
    let mut n = 0;
    for line in lines {
        let line = line?;
        if n == rows {
            return Err(bad(
                n + 2,
                format!("more rows than the {rows} the part summary counts"),
            ));
        }
        check(n, &line).map_err(|m| bad(n + 2, m))?;
        writeln!(out, "{line}")?;
        n += 1;
    }
    if n < rows {
        return Err(bad(
            n + 2,
            format!("the file ends after {n} of the {rows} rows the part summary counts"),
        ));
    }
    Ok(())
}

/// Checks that a batch row is roll `id` (its first column).
pub(crate) fn check_roll_id(row: &str, id: u64) -> Result<(), String> {
    let first = row.split(',').next().unwrap_or_default();
    if first.parse() == Ok(id) {
        Ok(())
    } else {
        Err(format!("roll id `{first}`, expected {id}"))
    }
}

/// Reads a map row (`i,j,x,y,start_face,face,status,steps,time_s,sampled`, as
/// [`BasinMap::write_csv`](super::BasinMap::write_csv) writes it) that must be node
/// `(i, j)`; its floats are in shortest round-trip form, so the cell comes back exactly.
pub(crate) fn parse_map_row(row: &str, i: usize, j: usize) -> Result<Cell, String> {
    let cells: Vec<&str> = row.split(',').collect();
    let [ri, rj, _, _, start_face, face, status, steps, time_s, sampled] = cells[..] else {
        return Err(format!("{} cells, expected 10", cells.len()));
    };
    if (ri.parse(), rj.parse()) != (Ok(i), Ok(j)) {
        return Err(format!("cell ({ri}, {rj}), expected ({i}, {j})"));
    }
    let number = |what: &str, s: &str| format!("{what} `{s}` is not valid");
    let face = match face {
        "" => None,
        f => Some(
            f.parse::<u8>()
                .ok()
                .filter(|f| (1..=6).contains(f))
                .ok_or_else(|| number("face", f))?,
        ),
    };
    let status = Status::from_name(status).ok_or_else(|| number("status", status))?;
    Ok(Cell {
        outcome: Outcome {
            status,
            face,
            steps: steps.parse().map_err(|_| number("steps", steps))?,
            time_s: time_s.parse().map_err(|_| number("time_s", time_s))?,
        },
        start_face: start_face
            .parse::<u8>()
            .ok()
            .filter(|f| (1..=6).contains(f))
            .ok_or_else(|| number("start_face", start_face))?,
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
        copy_rows(text.as_bytes(), &mut out, "id,x", rows, &mut |n, row| {
            check_roll_id(row, 10 + n)
        })
        .map_err(|e| e.to_string())?;
        Ok(String::from_utf8(out).unwrap())
    }

    #[test]
    fn rows_are_copied_after_their_checks() {
        assert_eq!(copy("id,x\n10,a\n11,b\n", 2).unwrap(), "10,a\n11,b\n");
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
        let c = parse_map_row("3,1,-60,0.1,2,5,settled,1234,1.2345000000000002,1", 3, 1).unwrap();
        assert_eq!(c.outcome.face, Some(5));
        assert_eq!(c.outcome.status, Status::Settled);
        assert_eq!(c.outcome.steps, 1234);
        assert_eq!(c.outcome.time_s, 1.2345000000000002);
        assert_eq!((c.start_face, c.sampled), (2, true));
        let t = parse_map_row("0,0,1,1,6,,timeout,9,3,0", 0, 0).unwrap();
        assert_eq!(
            (t.outcome.face, t.outcome.status, t.sampled),
            (None, Status::Timeout, false)
        );
        assert_eq!(
            parse_map_row("0,0,1,1,6,,timeout,9,3,0", 1, 0).unwrap_err(),
            "cell (0, 0), expected (1, 0)"
        );
        assert_eq!(
            parse_map_row("0,0,1,1,6,7,settled,9,3,0", 0, 0).unwrap_err(),
            "face `7` is not valid"
        );
        assert_eq!(parse_map_row("0,0,1", 0, 0).unwrap_err(), "3 cells, expected 10");
    }
}
