//! Roll records as Parquet: the compact per-roll format for sweeps too large for CSV, read
//! directly by pandas (`read_parquet`), polars, DuckDB or R's arrow.
//!
//! The columns are the CSV's, in the same order, with the same names and types. Columns
//! that do not vary (a fixed height or orientation) are dictionary
//! encoded into almost nothing, the outcome columns into a few bits, the ids delta encoded;
//! the random draws themselves stay full 8-byte doubles (they are what makes a roll
//! reproducible bit for bit). No compression codec: random doubles do not compress, and a
//! codec would cost build time for nothing.
//!
//! Row groups hold [`ROW_GROUP`] rolls counted from the first record written, so the file
//! depends only on the records in it: a merge that writes the shards' records in order
//! writes the very bytes of a one-machine run.

use crate::ics::{SpinColumns, initial_column_names};
use crate::record::RollRecord;
use dicesim_physics::{FirstImpact, InitialCondition, Outcome, Status};
use parquet::basic::{Compression, Encoding};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int32Type, Int64Type};
use parquet::errors::ParquetError;
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::file::writer::SerializedFileWriter;
use parquet::record::Field;
use parquet::schema::parser::parse_message_type;
use std::io::Write;
use std::sync::Arc;

/// The key of the file's key-value metadata that says where its records came from.
pub(crate) const PROVENANCE_KEY: &str = "dicesim";

/// Rolls per row group: readers load a group at a time, and the writer buffers one
/// (~10 MB of records).
pub(crate) const ROW_GROUP: usize = 65_536;

/// The Parquet schema: the CSV's columns, by the same names and of the same types (a face
/// that is not there is a null, and so is the other spin form's in a file of both).
fn schema(spin: SpinColumns) -> String {
    let names = initial_column_names();
    let mut fields = vec!["REQUIRED INT64 id (INTEGER(64,false));".to_string()];
    for k in spin.present() {
        let spin_cell = (4..10).contains(&k);
        let repetition = if spin_cell && spin == SpinColumns::Both {
            "OPTIONAL"
        } else {
            "REQUIRED"
        };
        fields.push(format!("{repetition} DOUBLE {};", names[k]));
    }
    fields.extend(
        [
            "REQUIRED INT32 start_face (INTEGER(8,false));",
            "OPTIONAL INT32 face (INTEGER(8,false));",
            "REQUIRED BYTE_ARRAY status (STRING);",
            "REQUIRED INT64 steps (INTEGER(64,false));",
            "REQUIRED DOUBLE time_s;",
            "REQUIRED INT64 impacts (INTEGER(64,false));",
            "OPTIONAL INT64 first_impact_steps (INTEGER(64,false));",
            "OPTIONAL DOUBLE first_impact_time_s;",
            "OPTIONAL INT32 first_impact_face_down (INTEGER(8,false));",
        ]
        .map(String::from),
    );
    format!("message roll {{ {} }}", fields.join(" "))
}

/// Writes roll records as they come, a row group at a time.
pub struct RecordsWriter<W: Write + Send> {
    file: SerializedFileWriter<W>,
    spin: SpinColumns,
    group: Vec<RollRecord>,
}

impl<W: Write + Send> RecordsWriter<W> {
    /// A writer of records with spin columns `spin` whose file carries `provenance` (where
    /// the records came from) as the key-value metadata [`PROVENANCE_KEY`].
    pub fn new(sink: W, spin: SpinColumns, provenance: &str) -> Result<Self, ParquetError> {
        let schema = Arc::new(parse_message_type(&schema(spin))?);
        let props = WriterProperties::builder()
            .set_key_value_metadata(Some(vec![KeyValue::new(
                PROVENANCE_KEY.to_string(),
                provenance.to_string(),
            )]))
            .set_compression(Compression::UNCOMPRESSED)
            .set_max_row_group_row_count(Some(ROW_GROUP))
            .set_column_dictionary_enabled("id".into(), false)
            .set_column_encoding("id".into(), Encoding::DELTA_BINARY_PACKED)
            .build();
        Ok(RecordsWriter {
            file: SerializedFileWriter::new(sink, schema, Arc::new(props))?,
            spin,
            group: Vec::with_capacity(ROW_GROUP),
        })
    }

    pub fn write(&mut self, r: &RollRecord) -> Result<(), ParquetError> {
        self.group.push(*r);
        if self.group.len() == ROW_GROUP {
            self.flush_group()?;
        }
        Ok(())
    }

    /// Writes the last row group and the footer.
    pub fn finish(mut self) -> Result<W, ParquetError> {
        self.flush_group()?;
        self.file.into_inner()
    }

    fn flush_group(&mut self) -> Result<(), ParquetError> {
        if self.group.is_empty() {
            return Ok(());
        }
        let rows = std::mem::take(&mut self.group);
        let mut group = self.file.next_row_group()?;
        let mut columns = columns(self.spin).into_iter();
        while let Some(mut w) = group.next_column()? {
            let column = columns.next().expect("one column of the schema each");
            write_column(&mut w, column, self.spin, &rows)?;
            w.close()?;
        }
        group.close()?;
        self.group = rows;
        self.group.clear();
        Ok(())
    }
}

/// A column of a records file, in the schema's order.
#[derive(Debug, Clone, Copy)]
enum Column {
    Id,
    /// Initial-condition column `k` (of [`initial_column_names`]).
    Initial(usize),
    StartFace,
    Face,
    Status,
    Steps,
    Time,
    Impacts,
    FirstImpactSteps,
    FirstImpactTime,
    FirstImpactFaceDown,
}

/// The columns of a records file with spin columns `spin`, in the schema's order.
fn columns(spin: SpinColumns) -> Vec<Column> {
    std::iter::once(Column::Id)
        .chain(spin.present().map(Column::Initial))
        .chain([
            Column::StartFace,
            Column::Face,
            Column::Status,
            Column::Steps,
            Column::Time,
            Column::Impacts,
            Column::FirstImpactSteps,
            Column::FirstImpactTime,
            Column::FirstImpactFaceDown,
        ])
        .collect()
}

/// The value of initial-condition column `k` of a record: `None` for the spin form it was
/// not given.
fn initial_value(ic: &InitialCondition, k: usize) -> Option<f64> {
    let momentum = ic.angular_momentum;
    match k {
        0 => Some(ic.height),
        1..=3 => Some(ic.velocity[k - 1]),
        4..=6 => momentum.is_none().then_some(ic.angular_velocity[k - 4]),
        7..=9 => momentum.map(|l| l[k - 7]),
        _ => Some(ic.orientation[k - 10]),
    }
}

/// Writes `column` of `rows`.
fn write_column(
    w: &mut parquet::file::writer::SerializedColumnWriter<'_>,
    column: Column,
    spin: SpinColumns,
    rows: &[RollRecord],
) -> Result<(), ParquetError> {
    match column {
        Column::Id => {
            let ids: Vec<i64> = rows.iter().map(|r| r.id as i64).collect();
            w.typed::<Int64Type>().write_batch(&ids, None, None)?;
        }
        Column::Initial(k) => {
            let values: Vec<Option<f64>> = rows.iter().map(|r| initial_value(&r.initial, k)).collect();
            let present: Vec<f64> = values.iter().flatten().copied().collect();
            if (4..10).contains(&k) && spin == SpinColumns::Both {
                let levels: Vec<i16> = values.iter().map(|v| i16::from(v.is_some())).collect();
                w.typed::<DoubleType>()
                    .write_batch(&present, Some(&levels), None)?;
            } else {
                w.typed::<DoubleType>().write_batch(&present, None, None)?;
            }
        }
        Column::StartFace => {
            let faces: Vec<i32> = rows.iter().map(|r| i32::from(r.start_face)).collect();
            w.typed::<Int32Type>().write_batch(&faces, None, None)?;
        }
        Column::Face => {
            let levels: Vec<i16> = rows.iter().map(|r| i16::from(r.outcome.face.is_some())).collect();
            let faces: Vec<i32> = rows
                .iter()
                .filter_map(|r| r.outcome.face.map(i32::from))
                .collect();
            w.typed::<Int32Type>().write_batch(&faces, Some(&levels), None)?;
        }
        Column::Status => {
            let names: Vec<ByteArray> = rows
                .iter()
                .map(|r| ByteArray::from(r.outcome.status.name()))
                .collect();
            w.typed::<ByteArrayType>().write_batch(&names, None, None)?;
        }
        Column::Steps => {
            let steps: Vec<i64> = rows.iter().map(|r| r.outcome.steps as i64).collect();
            w.typed::<Int64Type>().write_batch(&steps, None, None)?;
        }
        Column::Time => {
            let times: Vec<f64> = rows.iter().map(|r| r.outcome.time_s).collect();
            w.typed::<DoubleType>().write_batch(&times, None, None)?;
        }
        Column::Impacts => {
            let impacts: Vec<i64> = rows.iter().map(|r| r.outcome.impacts as i64).collect();
            w.typed::<Int64Type>().write_batch(&impacts, None, None)?;
        }
        Column::FirstImpactSteps | Column::FirstImpactTime | Column::FirstImpactFaceDown => {
            let levels: Vec<i16> = rows
                .iter()
                .map(|r| i16::from(r.outcome.first_impact.is_some()))
                .collect();
            let firsts = rows.iter().filter_map(|r| r.outcome.first_impact);
            match column {
                Column::FirstImpactSteps => {
                    let steps: Vec<i64> = firsts.map(|f| f.step as i64).collect();
                    w.typed::<Int64Type>().write_batch(&steps, Some(&levels), None)?;
                }
                Column::FirstImpactTime => {
                    let times: Vec<f64> = firsts.map(|f| f.time_s).collect();
                    w.typed::<DoubleType>().write_batch(&times, Some(&levels), None)?;
                }
                _ => {
                    let faces: Vec<i32> = firsts.map(|f| i32::from(f.face_down)).collect();
                    w.typed::<Int32Type>().write_batch(&faces, Some(&levels), None)?;
                }
            }
        }
    }
    Ok(())
}

/// Reads back every record of a file [`RecordsWriter`] wrote, in order, and checks its
/// schema is one this program writes (`spin`'s, where given) and, where `provenance` is
/// given, that the file says it came from there. Returns the file's spin columns.
pub fn read_records(
    file: std::fs::File,
    provenance: Option<&str>,
    spin: Option<SpinColumns>,
    each: &mut dyn FnMut(RollRecord) -> Result<(), String>,
) -> Result<SpinColumns, String> {
    let reader = untrusted(|| SerializedFileReader::new(file).map_err(|e| e.to_string()))?;
    if let Some(expected) = provenance {
        let found = reader
            .metadata()
            .file_metadata()
            .key_value_metadata()
            .and_then(|kv| kv.iter().find(|kv| kv.key == PROVENANCE_KEY))
            .and_then(|kv| kv.value.as_deref());
        if found != Some(expected) {
            return Err(format!(
                "its provenance (metadata `{PROVENANCE_KEY}`) is {}, not this sweep's",
                found.map_or("missing".to_string(), |f| format!("`{f}`"))
            ));
        }
    }
    let layout = layout_of(&reader, spin)?;
    let columns = columns(layout);
    let mut rows = untrusted(|| reader.get_row_iter(None).map_err(|e| e.to_string()))?;
    while let Some(row) = untrusted(|| Ok(rows.next()))? {
        let row = row.map_err(|e| e.to_string())?;
        let fields: Vec<&Field> = row.get_column_iter().map(|(_, f)| f).collect();
        each(record_from(&columns, &fields)?)?;
    }
    Ok(layout)
}

/// The spin columns of a records file [`RecordsWriter`] wrote, read from its schema.
pub fn records_spin(file: std::fs::File) -> Result<SpinColumns, String> {
    let reader = untrusted(|| SerializedFileReader::new(file).map_err(|e| e.to_string()))?;
    layout_of(&reader, None)
}

/// The spin columns whose schema is the file's (`spin`'s only, where given).
fn layout_of(
    reader: &SerializedFileReader<std::fs::File>,
    spin: Option<SpinColumns>,
) -> Result<SpinColumns, String> {
    let names = |fields: &[parquet::schema::types::TypePtr]| -> Vec<String> {
        fields.iter().map(|f| f.name().to_string()).collect()
    };
    let found = names(reader.metadata().file_metadata().schema().get_fields());
    let layouts = [
        SpinColumns::AngularVelocity,
        SpinColumns::AngularMomentum,
        SpinColumns::Both,
    ];
    let layout = layouts
        .into_iter()
        .filter(|s| spin.is_none_or(|e| e == *s))
        .find(|&s| {
            parse_message_type(&schema(s)).is_ok_and(|expected| names(expected.get_fields()) == found)
        });
    layout.ok_or_else(|| {
        format!(
            "not a dicesim roll file of this sweep: its columns are {}",
            found.join(", ")
        )
    })
}

/// Runs one step of the Parquet decoder over bytes that may be damaged, a panic of the
/// decoder as an error: parquet 60 panics on some corrupt pages where it should return one
/// (apache/arrow-rs#11121), and a damaged part is bad input to refuse, not a crash. Only the
/// decoder's own calls run inside, so a panic of this program's code is never hidden.
fn untrusted<T>(decode: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    quiet_decoder_panics::install();
    let result =
        quiet_decoder_panics::quietly(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(decode)));
    result.unwrap_or_else(|payload| {
        let why = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("the decoder stopped");
        Err(format!("its Parquet data is damaged ({why})"))
    })
}

/// A panic hook that stays silent while this thread decodes untrusted Parquet, so the refusal
/// is the one message a user reads; every other panic goes to the hook that was there before.
mod quiet_decoder_panics {
    use std::cell::Cell;
    use std::sync::Once;

    thread_local! {
        static QUIET: Cell<bool> = const { Cell::new(false) };
    }

    pub(super) fn install() {
        static INSTALL: Once = Once::new();
        INSTALL.call_once(|| {
            let previous = std::panic::take_hook();
            std::panic::set_hook(Box::new(move |info| {
                if !QUIET.with(Cell::get) {
                    previous(info);
                }
            }));
        });
    }

    pub(super) fn quietly<T>(f: impl FnOnce() -> T) -> T {
        let before = QUIET.with(|q| q.replace(true));
        let result = f();
        QUIET.with(|q| q.set(before));
        result
    }
}

/// A record from the fields of one row, which are `columns`.
fn record_from(columns: &[Column], f: &[&Field]) -> Result<RollRecord, String> {
    if f.len() != columns.len() {
        return Err(format!("a row of {} fields, expected {}", f.len(), columns.len()));
    }
    let bad = |i: usize| format!("column {i} holds an unexpected value {:?}", f[i]);
    let mut initial: [Option<f64>; 13] = [None; 13];
    let mut r = RollRecord {
        id: 0,
        initial: InitialCondition::default(),
        start_face: 0,
        outcome: Outcome {
            status: Status::Settled,
            face: None,
            steps: 0,
            time_s: 0.0,
            impacts: 0,
            first_impact: None,
        },
    };
    // The first impact's three cells: all or none.
    let (mut first_step, mut first_time, mut first_face) = (None, None, None);
    for (i, column) in columns.iter().enumerate() {
        let double = || match f[i] {
            Field::Double(v) => Ok(Some(*v)),
            Field::Null => Ok(None),
            _ => Err(bad(i)),
        };
        let small = || match f[i] {
            Field::UByte(v) => Ok(Some(*v)),
            Field::Null => Ok(None),
            _ => Err(bad(i)),
        };
        let unsigned = || match f[i] {
            Field::ULong(v) => Ok(*v),
            _ => Err(bad(i)),
        };
        match column {
            Column::Id => r.id = unsigned()?,
            Column::Initial(k) => initial[*k] = double()?,
            Column::StartFace => r.start_face = small()?.ok_or_else(|| bad(i))?,
            Column::Face => r.outcome.face = small()?,
            Column::Status => {
                r.outcome.status = match f[i] {
                    Field::Str(s) => Status::from_name(s).ok_or_else(|| bad(i))?,
                    _ => return Err(bad(i)),
                }
            }
            Column::Steps => r.outcome.steps = unsigned()?,
            Column::Time => r.outcome.time_s = double()?.ok_or_else(|| bad(i))?,
            Column::Impacts => r.outcome.impacts = unsigned()?,
            Column::FirstImpactSteps => {
                first_step = match f[i] {
                    Field::ULong(v) => Some(*v),
                    Field::Null => None,
                    _ => return Err(bad(i)),
                }
            }
            Column::FirstImpactTime => first_time = double()?,
            Column::FirstImpactFaceDown => first_face = small()?,
        }
    }
    r.outcome.first_impact = match (first_step, first_time, first_face) {
        (Some(step), Some(time_s), Some(face_down)) => Some(FirstImpact {
            step,
            time_s,
            face_down,
        }),
        (None, None, None) => None,
        _ => return Err("a first impact with some of its cells empty".to_string()),
    };
    let at = |k: usize| {
        columns
            .iter()
            .position(|c| matches!(c, Column::Initial(j) if *j == k))
            .unwrap_or(0)
    };
    let required = |k: usize| initial[k].ok_or_else(|| bad(at(k)));
    let triple = |k: usize| match [initial[k], initial[k + 1], initial[k + 2]] {
        [Some(x), Some(y), Some(z)] => Ok(Some([x, y, z])),
        [None, None, None] => Ok(None),
        _ => Err(bad(at(k))),
    };
    r.initial.height = required(0)?;
    r.initial.velocity = [required(1)?, required(2)?, required(3)?];
    r.initial.orientation = [required(10)?, required(11)?, required(12)?];
    match (triple(4)?, triple(7)?) {
        (Some(w), None) => r.initial.angular_velocity = w,
        (None, Some(l)) => r.initial.angular_momentum = Some(l),
        _ => {
            return Err(format!(
                "{}: the spin is given once, as one of its forms",
                bad(at(4).max(at(7)))
            ));
        }
    }
    Ok(r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::RandomRanges;
    use crate::record::roll_record;
    use dicesim_physics::Params;
    use dicesim_setup::random::RandomDraws;

    fn records(n: u64) -> Vec<RollRecord> {
        let (ranges, base) = (RandomRanges::default(), InitialCondition::default());
        let params = Params::default();
        (0..n)
            .map(|i| roll_record(&params, &ranges.draw(&base, 1, i), i))
            .collect()
    }

    fn write(rs: &[RollRecord]) -> Vec<u8> {
        let spin = SpinColumns::of_starts(rs.iter().map(|r| &r.initial));
        let mut w = RecordsWriter::new(Vec::new(), spin, "{}").unwrap();
        for r in rs {
            w.write(r).unwrap();
        }
        w.finish().unwrap()
    }

    #[test]
    fn records_read_back_bit_for_bit() {
        let mut rs = records(300);
        // Unset and set angular momentum, a missing face, and the other statuses.
        rs[1].initial.angular_momentum = Some([1.5, -2.0, 1e-300]);
        rs[2].outcome.face = None;
        rs[2].outcome.status = Status::Timeout;
        rs[3].outcome.status = Status::Unstable;
        let bytes = write(&rs);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("r.parquet");
        std::fs::write(&path, &bytes).unwrap();
        let mut back = Vec::new();
        let spin = read_records(std::fs::File::open(&path).unwrap(), Some("{}"), None, &mut |r| {
            back.push(r);
            Ok(())
        })
        .unwrap();
        assert_eq!(spin, SpinColumns::Both);
        assert_eq!(back.len(), rs.len());
        for (a, b) in back.iter().zip(&rs) {
            // The angular velocity of a start given its momentum is not the spin: not kept.
            assert!(crate::record::same_record(a, b), "{a:?} {b:?}");
            assert_eq!(a.outcome.time_s.to_bits(), b.outcome.time_s.to_bits());
        }
    }

    #[test]
    fn the_file_depends_on_the_records_alone() {
        let rs = records(40);
        assert_eq!(write(&rs), write(&rs));
        let mut other = rs.clone();
        other[7].outcome.steps += 1;
        assert_ne!(write(&rs), write(&other));
    }

    #[test]
    fn a_panicking_decoder_step_is_an_error_naming_the_damage() {
        let e = untrusted::<()>(|| panic!("page header cut short")).unwrap_err();
        assert_eq!(e, "its Parquet data is damaged (page header cut short)");
        assert_eq!(untrusted(|| Ok(3)), Ok(3));
        assert_eq!(untrusted::<()>(|| Err("plain".into())), Err("plain".to_string()));
    }

    /// Every single-bit flip of a small records file is read back or refused, never a panic
    /// (the decoder's own panics included), and a flip that reads back changes no record the
    /// file does not also say changed (the content hash of a part is merge's check of that).
    #[test]
    fn every_bit_flip_is_read_or_refused_never_a_panic() {
        let rs = records(12);
        let bytes = write(&rs);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("r.parquet");
        // Every bit of every 7th byte: about 2 000 damaged files across header, pages and footer.
        for at in (0..bytes.len()).step_by(7) {
            for bit in 0..8 {
                let mut damaged = bytes.clone();
                damaged[at] ^= 1 << bit;
                std::fs::write(&path, &damaged).unwrap();
                let file = std::fs::File::open(&path).unwrap();
                let read = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    read_records(file, None, None, &mut |_| Ok(()))
                }));
                assert!(read.is_ok(), "a flip of bit {bit} at byte {at} panicked");
            }
        }
    }
}
