//! Initial conditions and roll records as CSV: one column layout for reading `--ics` files
//! and writing per-roll results, so a batch's output can be fed back as its input.

use crate::Error;
use crate::record::RollRecord;
use dicesim_physics::{InitialCondition, Outcome, Status};

/// The initial-condition columns, in output order (`id` first, then these).
pub(crate) const INITIAL_COLUMNS: [&str; COLUMNS] = [
    "height",
    "velocity_x",
    "velocity_y",
    "velocity_z",
    "angular_velocity_x",
    "angular_velocity_y",
    "angular_velocity_z",
    "angular_momentum_x",
    "angular_momentum_y",
    "angular_momentum_z",
    "yaw",
    "pitch",
    "roll",
];

/// The result columns of a per-roll file; an `--ics` file may carry them (they are ignored).
pub(crate) const RESULT_COLUMNS: [&str; 5] = ["start_face", "face", "status", "steps", "time_s"];

const COLUMNS: usize = 13;

/// The values of the initial-condition columns: the spin once, as the angular momentum
/// where one is set (the angular velocity is then not the spin, so its cells stay empty)
/// and as the angular velocity otherwise.
fn initial_values(ic: &InitialCondition) -> [Option<f64>; COLUMNS] {
    let l = ic.angular_momentum;
    let w = |i: usize| l.is_none().then_some(ic.angular_velocity[i]);
    [
        Some(ic.height),
        Some(ic.velocity[0]),
        Some(ic.velocity[1]),
        Some(ic.velocity[2]),
        w(0),
        w(1),
        w(2),
        l.map(|l| l[0]),
        l.map(|l| l[1]),
        l.map(|l| l[2]),
        Some(ic.orientation[0]),
        Some(ic.orientation[1]),
        Some(ic.orientation[2]),
    ]
}

/// The header of a per-roll CSV file.
pub fn records_csv_header() -> Vec<&'static str> {
    std::iter::once("id")
        .chain(INITIAL_COLUMNS)
        .chain(RESULT_COLUMNS)
        .collect()
}

/// One roll as a CSV record (floats in shortest round-trip form, so reading back is exact;
/// an unset angular momentum and a missing face are empty cells).
pub fn record_csv_row(r: &RollRecord) -> Vec<String> {
    let cell = |v: Option<f64>| v.map(|v| v.to_string()).unwrap_or_default();
    let mut row = vec![r.id.to_string()];
    row.extend(initial_values(&r.initial).map(cell));
    row.extend([
        r.start_face.to_string(),
        r.outcome.face.map(|f| f.to_string()).unwrap_or_default(),
        r.outcome.status.name().to_string(),
        r.outcome.steps.to_string(),
        r.outcome.time_s.to_string(),
    ]);
    row
}

/// [`record_csv_row`] as one line, its cells joined by commas, in a single allocation.
pub fn record_csv_line(r: &RollRecord) -> String {
    use std::fmt::Write;
    let mut line = String::with_capacity(192);
    // Writing into a String cannot fail.
    let _ = write!(line, "{}", r.id);
    for v in initial_values(&r.initial) {
        line.push(',');
        if let Some(v) = v {
            let _ = write!(line, "{v}");
        }
    }
    let _ = write!(line, ",{},", r.start_face);
    if let Some(f) = r.outcome.face {
        let _ = write!(line, "{f}");
    }
    let o = &r.outcome;
    let _ = write!(line, ",{},{},{}", o.status.name(), o.steps, o.time_s);
    line
}

/// Reads back one row that [`record_csv_row`] wrote: exactly its cells in exactly its form
/// (a row that parses but is written differently, e.g. `1.50` for `1.5` or a cell in
/// quotes, is not a row this program wrote and is refused). The values themselves are
/// checked by [`check_record`](crate::record::check_record).
pub fn parse_record_csv_row(row: &str) -> Result<RollRecord, String> {
    // The header is built only for an error: a merge reads millions of rows.
    let name = |k: usize| records_csv_header()[k];
    let columns = 1 + INITIAL_COLUMNS.len() + RESULT_COLUMNS.len();
    let mut cells: [&str; 1 + INITIAL_COLUMNS.len() + RESULT_COLUMNS.len()] = [""; _];
    let mut found = 0;
    for cell in row.split(',') {
        if let Some(slot) = cells.get_mut(found) {
            *slot = cell;
        }
        found += 1;
    }
    if found != columns {
        return Err(format!("{found} cells, expected {columns}"));
    }
    let bad = |k: usize| format!("`{}` = `{}` is not valid", name(k), cells[k].escape_debug());
    let number = |k: usize| cells[k].parse::<f64>().map_err(|_| bad(k));
    let optional = |k: usize| match cells[k] {
        "" => Ok(None),
        _ => number(k).map(Some),
    };
    let momentum = [optional(8)?, optional(9)?, optional(10)?];
    let spin_given = momentum.iter().all(Option::is_some);
    let angular_velocity = if spin_given {
        if let Some(k) = (5..8).find(|&k| !cells[k].is_empty()) {
            return Err(bad(k));
        }
        InitialCondition::default().angular_velocity
    } else {
        [number(5)?, number(6)?, number(7)?]
    };
    let small = |k: usize| cells[k].parse::<u8>().map_err(|_| bad(k));
    let id_at = 0;
    let r = RollRecord {
        id: cells[id_at].parse().map_err(|_| bad(id_at))?,
        initial: InitialCondition {
            height: number(1)?,
            velocity: [number(2)?, number(3)?, number(4)?],
            angular_velocity,
            angular_momentum: match momentum {
                [Some(x), Some(y), Some(z)] => Some([x, y, z]),
                [None, None, None] => None,
                _ => return Err(bad(8)),
            },
            orientation: [number(11)?, number(12)?, number(13)?],
        },
        start_face: small(14)?,
        outcome: Outcome {
            face: match cells[15] {
                "" => None,
                _ => Some(small(15)?),
            },
            status: Status::from_name(cells[16]).ok_or_else(|| bad(16))?,
            steps: cells[17].parse().map_err(|_| bad(17))?,
            time_s: number(18)?,
        },
    };
    // The one accepted spelling of every cell is the one this program writes. The row is
    // written once into one buffer and compared whole (the cells hold no commas, so equal
    // lines are equal cells); only a row that differs is taken apart to name the cell.
    if record_csv_line(&r) != row {
        let k = (record_csv_row(&r).iter().zip(&cells))
            .position(|(a, b)| a != b)
            .unwrap_or(0);
        return Err(format!(
            "`{}` = `{}` is not written as this program writes it",
            name(k),
            cells[k].escape_debug()
        ));
    }
    Ok(r)
}

/// Writes the header and one record per roll: what `--ics` reads back (the tests' way to
/// make such a file; `batch` streams the same rows).
#[cfg(test)]
pub(crate) fn write_records_csv(out: impl std::io::Write, records: &[RollRecord]) -> std::io::Result<()> {
    let mut csv = csv::Writer::from_writer(out);
    csv.write_record(records_csv_header()).map_err(crate::csv_io)?;
    for r in records {
        csv.write_record(record_csv_row(r)).map_err(crate::csv_io)?;
    }
    csv.flush()
}

/// Reads an `--ics` file: a header with `id` and any of [`INITIAL_COLUMNS`] (result columns
/// are allowed and ignored). Missing columns and empty cells take `base`'s values; rows
/// that give spin as angular velocity only drop `base`'s angular momentum (as `--set` does);
/// `inertia` (g·cm²) restates `base`'s spin when only some angular-momentum components are
/// given. Every row is checked against the allowed ranges; the first bad row is an error
/// naming its line (1-based), and nothing is returned.
pub fn parse_initial_conditions(
    text: &str,
    base: &InitialCondition,
    inertia: f64,
) -> Result<Vec<(u64, InitialCondition)>, Error> {
    let bad = |line: usize, message: String| Error::Ics { line, message };
    // Quoted cells, a byte-order mark, blank lines and `#` comment lines are the reader's.
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    // The reader's line count leaves out blank lines, and a record's byte offset is where
    // the reader began looking for it: step over the blank and comment lines from there.
    let bytes = text.as_bytes();
    let line_at = |p: Option<&csv::Position>| {
        let mut at = p.map_or(0, |p| p.byte() as usize).min(bytes.len());
        loop {
            match bytes.get(at) {
                Some(b'\n' | b'\r') => at += 1,
                Some(b'#') => {
                    at += bytes[at..]
                        .iter()
                        .position(|&b| b == b'\n')
                        .unwrap_or(bytes.len() - at)
                }
                _ => break,
            }
        }
        bytes[..at].iter().filter(|&&b| b == b'\n').count() + 1
    };
    let line_of = |e: &csv::Error| line_at(e.position());
    let mut records = reader.records();
    let header = match records.next() {
        None => return Err(bad(1, "empty file: expected a header with `id`".to_string())),
        Some(Err(e)) => return Err(bad(line_of(&e), e.to_string())),
        Some(Ok(h)) => h,
    };
    let header_line = line_at(header.position());
    // For each column: Some(index into INITIAL_COLUMNS), or None for `id` / result columns.
    let mut columns: Vec<Option<usize>> = Vec::new();
    let mut id_column = None;
    for (i, name) in header.iter().enumerate() {
        if name == "id" {
            id_column = Some(i);
            columns.push(None);
        } else if let Some(k) = INITIAL_COLUMNS.iter().position(|c| *c == name) {
            if columns.contains(&Some(k)) {
                return Err(bad(header_line, format!("column `{name}` appears twice")));
            }
            columns.push(Some(k));
        } else if RESULT_COLUMNS.contains(&name) {
            columns.push(None);
        } else {
            return Err(bad(
                header_line,
                format!(
                    "unknown column `{name}`; expected `id` and any of {}",
                    INITIAL_COLUMNS.join(", ")
                ),
            ));
        }
    }
    let id_column = id_column.ok_or_else(|| bad(header_line, "the header has no `id` column".to_string()))?;
    let mut seen_ids = std::collections::HashMap::new();
    let base_momentum: [f64; 3] = base.angular_momentum_for(inertia).into();
    let mut out = Vec::new();
    for record in records {
        let record = record.map_err(|e| bad(line_of(&e), e.to_string()))?;
        let line = line_at(record.position());
        let cells: Vec<&str> = record.iter().collect();
        if cells.len() != columns.len() {
            return Err(bad(
                line,
                format!(
                    "{} cells, but the header has {} columns",
                    cells.len(),
                    columns.len()
                ),
            ));
        }
        let id: u64 = cells[id_column].parse().map_err(|_| {
            bad(
                line,
                format!("id `{}` is not a whole number ≥ 0", cells[id_column]),
            )
        })?;
        if let Some(first) = seen_ids.insert(id, line) {
            return Err(bad(line, format!("id {id} was already given on line {first}")));
        }
        let mut given: [Option<f64>; COLUMNS] = [None; COLUMNS];
        for (cell, column) in cells.iter().zip(&columns) {
            if let (Some(k), false) = (column, cell.is_empty()) {
                let v: f64 = cell.parse().map_err(|_| {
                    bad(
                        line,
                        format!("`{}` = `{cell}` is not a number", INITIAL_COLUMNS[*k]),
                    )
                })?;
                given[*k] = Some(v);
            }
        }
        if given[4..7].iter().any(Option::is_some) && given[7..10].iter().any(Option::is_some) {
            // The spin twice: fine only where both say the same (L = I·ω to rounding).
            let w: [f64; 3] = std::array::from_fn(|i| given[4 + i].unwrap_or(base.angular_velocity[i]));
            let l: [f64; 3] = std::array::from_fn(|i| given[7 + i].unwrap_or(base_momentum[i]));
            let agree =
                (0..3).all(|i| (w[i] * inertia - l[i]).abs() <= 1e-9 * l[i].abs().max(inertia * 1e-9));
            if !agree {
                return Err(bad(
                    line,
                    format!(
                        "the spin is given twice and the two disagree: angular_velocity {w:?} rad/s \
                         is angular momentum {:?} g·cm²/s, not {l:?}; leave one of them empty",
                        w.map(|x| x * inertia)
                    ),
                ));
            }
        }
        let pick = |k: usize, default: f64| given[k].unwrap_or(default);
        let mut ic = *base;
        ic.height = pick(0, base.height);
        ic.velocity = std::array::from_fn(|i| pick(1 + i, base.velocity[i]));
        ic.angular_velocity = std::array::from_fn(|i| pick(4 + i, base.angular_velocity[i]));
        if given[7..10].iter().any(Option::is_some) {
            ic.angular_momentum = Some(std::array::from_fn(|i| pick(7 + i, base_momentum[i])));
        } else if given[4..7].iter().any(Option::is_some) {
            ic.angular_momentum = None;
        }
        ic.orientation = std::array::from_fn(|i| pick(10 + i, base.orientation[i]));
        ic.validate().map_err(|e| {
            bad(
                line,
                format!("{} (id {id})", e.to_string().replace("initial.", "")),
            )
        })?;
        out.push((id, ic));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use dicesim_physics::Params;

    #[test]
    fn spreadsheet_headers_are_read_and_repeated_ids_refused() {
        let base = InitialCondition::default();
        let ics = parse_initial_conditions("\u{feff}\"id\",\"height\"\n3,2.5\n", &base, INERTIA).unwrap();
        assert_eq!((ics[0].0, ics[0].1.height), (3, 2.5));
        let e = parse_initial_conditions("id,height\n1,2\n1,3\n", &base, INERTIA).unwrap_err();
        assert_eq!(e.to_string(), "line 3: id 1 was already given on line 2");
    }

    const INERTIA: f64 = 16.0 / 3.0;

    /// The one-buffer line a merge compares and writes is the csv writer's row: with and
    /// without an angular momentum and a face, and with floats that need e-notation.
    #[test]
    fn the_records_line_is_the_csv_writers_row() {
        let settled = crate::roll_record(&Params::default(), &InitialCondition::default(), 7);
        let mut timeout = settled;
        timeout.id = u64::MAX;
        timeout.outcome.face = None;
        timeout.outcome.status = Status::Timeout;
        timeout.initial.angular_momentum = Some([1e-300, -0.0, 12345678.9]);
        timeout.initial.velocity = [f64::MIN_POSITIVE, -1.5e21, 0.1];
        for r in [settled, timeout] {
            let mut csv = Vec::new();
            write_records_csv(&mut csv, &[r]).unwrap();
            let csv = String::from_utf8(csv).unwrap();
            assert_eq!(csv.lines().nth(1).unwrap(), record_csv_line(&r));
            assert_eq!(parse_record_csv_row(&record_csv_line(&r)).unwrap(), r);
        }
    }

    #[test]
    fn missing_columns_and_cells_take_the_base() {
        let base = InitialCondition {
            velocity: [1.0, 2.0, 3.0],
            ..Default::default()
        };
        let text = "id,height,velocity_y,yaw\n7,4.5,,30\n\n# a comment\n8,2,-5,0\n";
        let ics = parse_initial_conditions(text, &base, INERTIA).unwrap();
        assert_eq!(ics.len(), 2);
        assert_eq!(ics[0].0, 7);
        assert_eq!(ics[0].1.height, 4.5);
        assert_eq!(ics[0].1.velocity, [1.0, 2.0, 3.0]);
        assert_eq!(ics[0].1.orientation, [30.0, 0.0, 0.0]);
        assert_eq!(ics[1].1.velocity, [1.0, -5.0, 3.0]);
    }

    #[test]
    fn spin_forms() {
        let base = InitialCondition {
            angular_momentum: Some([INERTIA, 0.0, 0.0]),
            ..Default::default()
        };
        let ics = parse_initial_conditions("id,angular_velocity_z\n1,4", &base, INERTIA).unwrap();
        assert_eq!(ics[0].1.angular_momentum, None);
        let ics = parse_initial_conditions("id,angular_momentum_y\n1,4", &base, INERTIA).unwrap();
        assert_eq!(ics[0].1.angular_momentum, Some([INERTIA, 4.0, 0.0]));
        let ics = parse_initial_conditions("id,height\n1,4", &base, INERTIA).unwrap();
        assert_eq!(ics[0].1.angular_momentum, base.angular_momentum);
        // Both forms in one row: accepted where they agree, refused where they do not.
        let both = format!("id,angular_velocity_x,angular_momentum_x\n1,2,{}", 2.0 * INERTIA);
        let ics = parse_initial_conditions(&both, &base, INERTIA).unwrap();
        assert_eq!(ics[0].1.angular_momentum, Some([2.0 * INERTIA, 0.0, 0.0]));
        let e = parse_initial_conditions("id,angular_velocity_x,angular_momentum_x\n1,2,5", &base, INERTIA)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("line 2: the spin is given twice and the two disagree"),
            "{e}"
        );
        // One form per row in one file: each row's own.
        let mixed = "id,angular_velocity_x,angular_momentum_x\n1,2,\n2,,5\n";
        let ics = parse_initial_conditions(mixed, &InitialCondition::default(), INERTIA).unwrap();
        assert_eq!(ics[0].1.angular_momentum, None);
        assert_eq!(ics[1].1.angular_momentum, Some([5.0, 0.0, 0.0]));
    }

    #[test]
    fn bad_rows_name_their_line() {
        let base = InitialCondition::default();
        let e = |t: &str| {
            parse_initial_conditions(t, &base, INERTIA)
                .unwrap_err()
                .to_string()
        };
        assert_eq!(
            e("id,height\n1,2\n\n2,abc\n"),
            "line 4: `height` = `abc` is not a number"
        );
        assert_eq!(
            e("id,height\n1,2,3\n"),
            "line 2: 3 cells, but the header has 2 columns"
        );
        assert_eq!(
            e("id,height\n1,-3\n"),
            "line 2: `height` = -3 is outside the allowed range 0 to 1000 cm (id 1)"
        );
        assert!(e("id,heigth\n").starts_with("line 1: unknown column `heigth`"));
        assert_eq!(e("height\n2\n"), "line 1: the header has no `id` column");
        assert_eq!(e("id,height\nx,2\n"), "line 2: id `x` is not a whole number ≥ 0");
    }

    #[test]
    fn quoted_cells_and_a_byte_order_mark_are_read() {
        let base = InitialCondition::default();
        let text = "\u{feff}id,\"height\",yaw\r\n\"3\", 2.5 ,\"-45\"\r\n";
        let ics = parse_initial_conditions(text, &base, INERTIA).unwrap();
        assert_eq!(
            ics,
            vec![(
                3,
                InitialCondition {
                    height: 2.5,
                    orientation: [-45.0, 0.0, 0.0],
                    ..base
                }
            )]
        );
    }

    #[test]
    fn records_read_back_exactly() {
        let p = Params::default();
        let ics = [
            InitialCondition {
                height: 3.1,
                velocity: [0.1, -7.3, 0.0],
                angular_velocity: [1.0 / 3.0, 2.0, -5.5],
                orientation: [10.0, 20.0, 30.0],
                ..Default::default()
            },
            InitialCondition {
                angular_momentum: Some([0.7, 0.0, -1.0]),
                ..Default::default()
            },
        ];
        let records: Vec<RollRecord> = ics
            .iter()
            .enumerate()
            .map(|(i, ic)| super::super::roll_record(&p, ic, i as u64))
            .collect();
        let mut bytes = Vec::new();
        write_records_csv(&mut bytes, &records).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        let back = parse_initial_conditions(&text, &InitialCondition::default(), INERTIA).unwrap();
        assert_eq!(back, vec![(0, ics[0]), (1, ics[1])]);
    }
}
