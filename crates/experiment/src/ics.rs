//! Initial conditions and roll records as CSV: one column layout for reading `--ics` files
//! and writing per-roll results, so a batch's output can be fed back as its input.
//!
//! Every numeric column is named with its unit (`height_cm`, `velocity_x_cm_per_s`), reals
//! are written as reals, and the spin columns a file holds are those its rolls were given:
//! the angular velocity, the angular momentum, or both where rolls of one file differ (each
//! row then leaves the other form's cells empty), so no column is empty in every row.

use crate::Error;
use crate::columns::{COLUMNS, Cell, RecordColumn, Type, record_from_cells};
use crate::record::RollRecord;
use dicesim_physics::InitialCondition;
use dicesim_setup::number::Real;
use std::sync::LazyLock;

pub use crate::columns::{SpinColumns, records_columns};

const COLUMNS_OF_START: usize = 13;

/// The start's columns, in output order (`id` first, then these): [`COLUMNS`]' reals of
/// the throw.
fn start_columns() -> impl Iterator<Item = &'static RecordColumn> {
    COLUMNS.iter().filter(|c| c.of_start())
}

/// The initial-condition columns with their units: `height_cm`, …, `roll_deg`.
pub(crate) fn initial_column_names() -> &'static [String; COLUMNS_OF_START] {
    static NAMES: LazyLock<[String; COLUMNS_OF_START]> = LazyLock::new(|| {
        let names: Vec<String> = start_columns().map(|c| c.name().to_string()).collect();
        names.try_into().expect("13 values of a start")
    });
    &NAMES
}

/// The names an `--ics` file of dicesim 0.1 used, still read: the same without their units.
fn initial_column_old_names() -> impl Iterator<Item = &'static str> {
    start_columns().map(RecordColumn::quantity)
}

impl SpinColumns {
    /// The spin columns a records header names, if it is one of the three this program writes.
    pub fn of_header(header: &str) -> Option<SpinColumns> {
        SpinColumns::ALL
            .into_iter()
            .find(|&s| records_csv_header(s) == header)
    }
}

/// The header line of a per-roll CSV file.
pub fn records_csv_header(spin: SpinColumns) -> String {
    crate::data_file::header(&records_columns(spin))
}

/// Appends one roll as a CSV line (without its line end) to `line`: reals in shortest
/// round-trip form with their point, so reading back is exact and every reader types them
/// as reals; the other spin form's cells and a missing face are empty. The cells are
/// numbers and status names, which CSV never quotes.
pub fn write_record_line(line: &mut Vec<u8>, r: &RollRecord, spin: SpinColumns) {
    debug_assert!(spin.holds(&r.initial), "a start the columns cannot hold");
    for (k, column) in spin.columns().iter().enumerate() {
        if k > 0 {
            line.push(b',');
        }
        write_cell(line, (column.get)(r));
    }
}

/// Appends one cell as a CSV writes it: nothing for an empty one.
pub(crate) fn write_cell(line: &mut Vec<u8>, cell: Cell<'_>) {
    match cell {
        Cell::Empty => {}
        Cell::Whole(n) => write_whole(line, n),
        Cell::Real(x) => Real(x).write_to(line),
        Cell::Word(w) => line.extend_from_slice(w.as_bytes()),
    }
}

/// Appends a whole number's decimal digits.
fn write_whole(line: &mut Vec<u8>, n: u64) {
    let mut digits = [0u8; 20];
    let mut at = digits.len();
    let mut n = n;
    loop {
        at -= 1;
        digits[at] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    line.extend_from_slice(&digits[at..]);
}

/// [`write_record_line`] as a new line.
pub fn record_csv_line(r: &RollRecord, spin: SpinColumns) -> String {
    let mut line = Vec::with_capacity(192);
    write_record_line(&mut line, r, spin);
    String::from_utf8(line).expect("a record's line is ASCII")
}

/// The cells of a record's line, each as written.
pub fn record_csv_row(r: &RollRecord, spin: SpinColumns) -> Vec<String> {
    record_csv_line(r, spin).split(',').map(str::to_string).collect()
}

/// A CSV cell of a column of type `ty` as its value (an empty cell as none); `None` for text
/// that is not one.
fn read_cell(text: &str, ty: Type) -> Option<Cell<'_>> {
    Some(match (text, ty) {
        ("", _) => Cell::Empty,
        (_, Type::Count | Type::Face) => Cell::Whole(text.parse().ok()?),
        (_, Type::Real) => Cell::Real(text.parse().ok()?),
        (_, Type::Word) => Cell::Word(text),
    })
}

/// Reads back one row that [`write_record_line`] wrote for columns `spin`: exactly its
/// cells in exactly its form (a row that parses but is written differently, e.g. `1.50` for
/// `1.5` or a cell in quotes, is not a row this program wrote and is refused). The values
/// themselves are checked by [`RecordCheck`](crate::columns::RecordCheck).
pub fn parse_record_line(row: &str, spin: SpinColumns) -> Result<RollRecord, String> {
    let columns = spin.columns();
    let cells: Vec<&str> = row.split(',').collect();
    if cells.len() != columns.len() {
        return Err(format!("{} cells, expected {}", cells.len(), columns.len()));
    }
    let at = |k: usize, why: &str| format!("`{}` = `{}` {why}", columns[k].name(), cells[k].escape_debug());
    let values = (cells.iter().zip(columns).enumerate())
        .map(|(k, (text, c))| read_cell(text, c.ty).ok_or_else(|| at(k, "is not valid")))
        .collect::<Result<Vec<Cell<'_>>, String>>()?;
    let r = record_from_cells(columns, &values, None).map_err(|(k, why)| at(k, why))?;
    // The one accepted spelling of every cell is the one this program writes. The row is
    // written once into one buffer and compared whole (the cells hold no commas, so equal
    // lines are equal cells); only a row that differs is taken apart to name the cell.
    let written = record_csv_line(&r, spin);
    if written != row {
        let k = (written.split(',').zip(&cells))
            .position(|(a, b)| a != *b)
            .unwrap_or(0);
        return Err(at(k, "is not written as this program writes it"));
    }
    Ok(r)
}

/// The record of a row of a seeded sweep whose start is `draw(id)`, if the row is exactly
/// what [`write_record_line`] writes for it; `None` for any other row (read it with
/// [`parse_record_line`], which names what differs). The start's cells are compared as
/// written, never parsed. `line` is a scratch buffer.
pub(crate) fn read_drawn_row(
    row: &[u8],
    spin: SpinColumns,
    draw: &dyn Fn(u64) -> InitialCondition,
    line: &mut Vec<u8>,
) -> Option<RollRecord> {
    let columns = spin.columns();
    // On the stack: a merge reads every row of every part here.
    let mut values = [Cell::Empty; COLUMNS.len()];
    let mut cells = std::str::from_utf8(row).ok()?.split(',');
    for (value, column) in values.iter_mut().zip(columns) {
        let text = cells.next()?;
        if !column.of_start() {
            *value = read_cell(text, column.ty)?;
        }
    }
    if cells.next().is_some() {
        return None;
    }
    let values = &values[..columns.len()];
    let r = record_from_cells(columns, values, Some(draw)).ok()?;
    line.clear();
    write_record_line(line, &r, spin);
    (line.as_slice() == row).then_some(r)
}

/// Writes the header and one record per roll: what `--ics` reads back (the tests' way to
/// make such a file; `batch` streams the same rows).
#[cfg(test)]
pub(crate) fn write_records_csv(
    out: &mut impl std::io::Write,
    records: &[RollRecord],
) -> std::io::Result<()> {
    let spin = SpinColumns::of_starts(records.iter().map(|r| &r.initial));
    writeln!(out, "{}", records_csv_header(spin))?;
    for r in records {
        writeln!(out, "{}", record_csv_line(r, spin))?;
    }
    Ok(())
}

/// Reads an `--ics` file: a header with `id` and any of the initial-condition columns
/// ([`initial_column_names`], or their names without units that dicesim 0.1 wrote; result
/// columns are allowed and ignored), so a batch's records file is one. Missing columns and empty cells take `base`'s values; rows
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
    // For each column: Some(index among the start's columns), or None for `id` / result columns.
    let mut columns: Vec<Option<usize>> = Vec::new();
    let mut id_column = None;
    for (i, name) in header.iter().enumerate() {
        if name == "id" {
            id_column = Some(i);
            columns.push(None);
        } else if let Some(k) = (initial_column_names().iter().position(|c| c == name))
            .or_else(|| initial_column_old_names().position(|c| c == name))
        {
            if columns.contains(&Some(k)) {
                return Err(bad(
                    header_line,
                    format!("column `{}` appears twice", initial_column_names()[k]),
                ));
            }
            columns.push(Some(k));
        } else if COLUMNS.iter().any(|c| !c.of_start() && c.name() == name) {
            columns.push(None);
        } else {
            return Err(bad(
                header_line,
                format!(
                    "unknown column `{name}`; expected `id` and any of {}",
                    initial_column_names().join(", ")
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
        let mut given: [Option<f64>; COLUMNS_OF_START] = [None; COLUMNS_OF_START];
        for (cell, column) in cells.iter().zip(&columns) {
            if let (Some(k), false) = (column, cell.is_empty()) {
                let v: f64 = cell.parse().map_err(|_| {
                    bad(
                        line,
                        format!("`{}` = `{cell}` is not a number", initial_column_names()[*k]),
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
    use dicesim_physics::{Params, Status};

    #[test]
    fn spreadsheet_headers_are_read_and_repeated_ids_refused() {
        let base = InitialCondition::default();
        let ics = parse_initial_conditions("\u{feff}\"id\",\"height\"\n3,2.5\n", &base, INERTIA).unwrap();
        assert_eq!((ics[0].0, ics[0].1.height), (3, 2.5));
        let e = parse_initial_conditions("id,height\n1,2\n1,3\n", &base, INERTIA).unwrap_err();
        assert_eq!(e.to_string(), "line 3: id 1 was already given on line 2");
    }

    const INERTIA: f64 = 16.0 / 3.0;

    /// A records line reads back as the record it was written from, in each spin layout,
    /// with reals that need an exponent or a point of their own (`15.0`, `-0.0`, `1e-300`).
    #[test]
    fn a_records_line_reads_back_as_its_record_in_every_layout() {
        let settled = crate::roll_record(&Params::default(), &InitialCondition::default(), 7);
        let mut timeout = settled;
        timeout.id = u64::MAX;
        timeout.outcome.face = None;
        timeout.outcome.status = Status::Timeout;
        timeout.initial.angular_momentum = Some([1e-300, -0.0, 12345678.9]);
        timeout.initial.velocity = [f64::MIN_POSITIVE, -1.5e21, 0.1];
        let line = record_csv_line(&settled, SpinColumns::AngularVelocity);
        assert!(line.starts_with("7,15.0,0.0,0.0,0.0,"), "{line}");
        for (r, spin) in [
            (settled, SpinColumns::AngularVelocity),
            (settled, SpinColumns::Both),
            (timeout, SpinColumns::AngularMomentum),
            (timeout, SpinColumns::Both),
        ] {
            let line = record_csv_line(&r, spin);
            assert_eq!(line.split(',').count(), records_columns(spin).len(), "{line}");
            assert_eq!(parse_record_line(&line, spin).unwrap(), r, "{line}");
        }
        let line = record_csv_line(&timeout, SpinColumns::Both);
        assert!(line.contains(",,,,1e-300,-0.0,12345678.9,"), "{line}");
        // A cell in another spelling is not what this program wrote.
        let respelled = record_csv_line(&settled, SpinColumns::AngularVelocity).replacen("15.0", "15", 1);
        assert_eq!(
            parse_record_line(&respelled, SpinColumns::AngularVelocity).unwrap_err(),
            "`height_cm` = `15` is not written as this program writes it"
        );
    }

    #[test]
    fn a_file_has_the_spin_columns_its_rolls_were_given() {
        let w = InitialCondition::default();
        let l = InitialCondition {
            angular_momentum: Some([1.0, 2.0, 3.0]),
            ..w
        };
        assert_eq!(SpinColumns::of_starts([]), SpinColumns::AngularVelocity);
        assert_eq!(SpinColumns::of_starts([&w, &w]), SpinColumns::AngularVelocity);
        assert_eq!(SpinColumns::of_starts([&l]), SpinColumns::AngularMomentum);
        assert_eq!(SpinColumns::of_starts([&w, &l]), SpinColumns::Both);
        let header = records_csv_header(SpinColumns::AngularVelocity);
        assert_eq!(
            header,
            "id,height_cm,velocity_x_cm_per_s,velocity_y_cm_per_s,velocity_z_cm_per_s,\
             angular_velocity_x_rad_per_s,angular_velocity_y_rad_per_s,angular_velocity_z_rad_per_s,\
             yaw_deg,pitch_deg,roll_deg,start_face,face,status,steps,time_s,\
             impacts,first_impact_steps,first_impact_time_s,first_impact_face_down"
        );
        assert!(
            records_csv_header(SpinColumns::AngularMomentum).contains(",angular_momentum_x_g_cm2_per_s,")
        );
        for spin in [
            SpinColumns::AngularVelocity,
            SpinColumns::AngularMomentum,
            SpinColumns::Both,
        ] {
            assert_eq!(SpinColumns::of_header(&records_csv_header(spin)), Some(spin));
        }
        assert_eq!(SpinColumns::of_header("id,height"), None);
    }

    #[test]
    fn a_records_file_is_an_ics_file_by_its_unit_names_and_the_old_names_still_read() {
        let base = InitialCondition::default();
        let text = "id,height_cm,yaw_deg,angular_velocity_x_rad_per_s,time_s\n3,2.5,10.0,4.0,0.7\n";
        let ics = parse_initial_conditions(text, &base, INERTIA).unwrap();
        assert_eq!(
            (
                ics[0].1.height,
                ics[0].1.orientation[0],
                ics[0].1.angular_velocity[0]
            ),
            (2.5, 10.0, 4.0)
        );
        let e = parse_initial_conditions("id,height,height_cm\n1,2,3\n", &base, INERTIA).unwrap_err();
        assert_eq!(e.to_string(), "line 1: column `height_cm` appears twice");
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
            "line 4: `height_cm` = `abc` is not a number"
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
