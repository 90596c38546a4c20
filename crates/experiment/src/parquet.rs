//! Roll records as Parquet: the compact per-roll format for sweeps too large for CSV, read
//! directly by pandas (`read_parquet`), polars, DuckDB or R's arrow.
//!
//! The columns are the CSV's, in the same order and with the same names. Columns that do
//! not vary (a fixed height or orientation, an unset angular momentum) are dictionary
//! encoded into almost nothing, the outcome columns into a few bits, the ids delta encoded;
//! the random draws themselves stay full 8-byte doubles (they are what makes a roll
//! reproducible bit for bit). No compression codec: random doubles do not compress, and a
//! codec would cost build time for nothing.
//!
//! Row groups hold [`ROW_GROUP`] rolls counted from the first record written, so the file
//! depends only on the records in it: a merge that writes the shards' records in order
//! writes the very bytes of a one-machine run.

use crate::ics::{INITIAL_COLUMNS, RESULT_COLUMNS};
use crate::record::RollRecord;
use dicesim_physics::{InitialCondition, Outcome, Status};
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

/// The Parquet schema: the CSV's columns (an unset angular momentum and a missing face
/// are nulls).
fn schema() -> String {
    let mut fields = vec!["REQUIRED INT64 id (INTEGER(64,false));".to_string()];
    for c in INITIAL_COLUMNS {
        let repetition = if c.starts_with("angular_momentum") {
            "OPTIONAL"
        } else {
            "REQUIRED"
        };
        fields.push(format!("{repetition} DOUBLE {c};"));
    }
    debug_assert_eq!(
        RESULT_COLUMNS,
        ["start_face", "face", "status", "steps", "time_s"]
    );
    fields.extend(
        [
            "REQUIRED INT32 start_face (INTEGER(8,false));",
            "OPTIONAL INT32 face (INTEGER(8,false));",
            "REQUIRED BYTE_ARRAY status (STRING);",
            "REQUIRED INT64 steps (INTEGER(64,false));",
            "REQUIRED DOUBLE time_s;",
        ]
        .map(String::from),
    );
    format!("message roll {{ {} }}", fields.join(" "))
}

/// Writes roll records as they come, a row group at a time.
pub struct RecordsWriter<W: Write + Send> {
    file: SerializedFileWriter<W>,
    group: Vec<RollRecord>,
}

impl<W: Write + Send> RecordsWriter<W> {
    /// A writer whose file carries `provenance` (where the records came from) as the
    /// key-value metadata [`PROVENANCE_KEY`].
    pub fn new(sink: W, provenance: &str) -> Result<Self, ParquetError> {
        let schema = Arc::new(parse_message_type(&schema())?);
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
        let mut column = 0;
        while let Some(mut w) = group.next_column()? {
            write_column(&mut w, column, &rows)?;
            w.close()?;
            column += 1;
        }
        group.close()?;
        self.group = rows;
        self.group.clear();
        Ok(())
    }
}

/// The values of initial-condition column `k` (of [`INITIAL_COLUMNS`]) of a record.
fn initial_value(ic: &InitialCondition, k: usize) -> Option<f64> {
    match k {
        0 => Some(ic.height),
        1..=3 => Some(ic.velocity[k - 1]),
        4..=6 => Some(ic.angular_velocity[k - 4]),
        7..=9 => ic.angular_momentum.map(|l| l[k - 7]),
        _ => Some(ic.orientation[k - 10]),
    }
}

/// Writes column `column` of `rows`.
fn write_column(
    w: &mut parquet::file::writer::SerializedColumnWriter<'_>,
    column: usize,
    rows: &[RollRecord],
) -> Result<(), ParquetError> {
    let optional = |values: Vec<Option<f64>>| {
        let levels: Vec<i16> = values.iter().map(|v| i16::from(v.is_some())).collect();
        let present: Vec<f64> = values.into_iter().flatten().collect();
        (present, levels)
    };
    let n = INITIAL_COLUMNS.len();
    match column {
        0 => {
            let ids: Vec<i64> = rows.iter().map(|r| r.id as i64).collect();
            w.typed::<Int64Type>().write_batch(&ids, None, None)?;
        }
        k if k <= n => {
            let values: Vec<Option<f64>> = rows.iter().map(|r| initial_value(&r.initial, k - 1)).collect();
            if INITIAL_COLUMNS[k - 1].starts_with("angular_momentum") {
                let (present, levels) = optional(values);
                w.typed::<DoubleType>()
                    .write_batch(&present, Some(&levels), None)?;
            } else {
                let values: Vec<f64> = values.into_iter().flatten().collect();
                w.typed::<DoubleType>().write_batch(&values, None, None)?;
            }
        }
        k => match k - n - 1 {
            0 => {
                let faces: Vec<i32> = rows.iter().map(|r| i32::from(r.start_face)).collect();
                w.typed::<Int32Type>().write_batch(&faces, None, None)?;
            }
            1 => {
                let levels: Vec<i16> = rows.iter().map(|r| i16::from(r.outcome.face.is_some())).collect();
                let faces: Vec<i32> = rows
                    .iter()
                    .filter_map(|r| r.outcome.face.map(i32::from))
                    .collect();
                w.typed::<Int32Type>().write_batch(&faces, Some(&levels), None)?;
            }
            2 => {
                let names: Vec<ByteArray> = rows
                    .iter()
                    .map(|r| ByteArray::from(r.outcome.status.name()))
                    .collect();
                w.typed::<ByteArrayType>().write_batch(&names, None, None)?;
            }
            3 => {
                let steps: Vec<i64> = rows.iter().map(|r| r.outcome.steps as i64).collect();
                w.typed::<Int64Type>().write_batch(&steps, None, None)?;
            }
            _ => {
                let times: Vec<f64> = rows.iter().map(|r| r.outcome.time_s).collect();
                w.typed::<DoubleType>().write_batch(&times, None, None)?;
            }
        },
    }
    Ok(())
}

/// Reads back every record of a file [`RecordsWriter`] wrote, in order, and checks its
/// schema is the one this program writes and, where `provenance` is given, that the file
/// says it came from there.
pub fn read_records(
    file: std::fs::File,
    provenance: Option<&str>,
    each: &mut dyn FnMut(RollRecord) -> Result<(), String>,
) -> Result<(), String> {
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
    let expected = parse_message_type(&schema()).map_err(|e| e.to_string())?;
    let names = |fields: &[parquet::schema::types::TypePtr]| -> Vec<String> {
        fields.iter().map(|f| f.name().to_string()).collect()
    };
    let found = reader.metadata().file_metadata().schema();
    if names(found.get_fields()) != names(expected.get_fields()) {
        return Err(format!(
            "not a dicesim roll file: its columns are {}",
            names(found.get_fields()).join(", ")
        ));
    }
    let mut rows = untrusted(|| reader.get_row_iter(None).map_err(|e| e.to_string()))?;
    while let Some(row) = untrusted(|| Ok(rows.next()))? {
        let row = row.map_err(|e| e.to_string())?;
        let fields: Vec<&Field> = row.get_column_iter().map(|(_, f)| f).collect();
        each(record_from(&fields)?)?;
    }
    Ok(())
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

/// A record from the fields of one row, in schema order.
fn record_from(f: &[&Field]) -> Result<RollRecord, String> {
    let bad = |i: usize| format!("column {i} holds an unexpected value {:?}", f[i]);
    let double = |i: usize| match f[i] {
        Field::Double(v) => Ok(Some(*v)),
        Field::Null => Ok(None),
        _ => Err(bad(i)),
    };
    let required = |i: usize| double(i)?.ok_or_else(|| bad(i));
    let unsigned = |i: usize| match f[i] {
        Field::ULong(v) => Ok(*v),
        _ => Err(bad(i)),
    };
    let small = |i: usize| match f[i] {
        Field::UByte(v) => Ok(Some(*v)),
        Field::Null => Ok(None),
        _ => Err(bad(i)),
    };
    let momentum = [double(8)?, double(9)?, double(10)?];
    let initial = InitialCondition {
        height: required(1)?,
        velocity: [required(2)?, required(3)?, required(4)?],
        angular_velocity: [required(5)?, required(6)?, required(7)?],
        angular_momentum: match momentum {
            [Some(x), Some(y), Some(z)] => Some([x, y, z]),
            [None, None, None] => None,
            _ => return Err(bad(8)),
        },
        orientation: [required(11)?, required(12)?, required(13)?],
    };
    let status = match f[16] {
        Field::Str(s) => Status::from_name(s).ok_or_else(|| bad(16))?,
        _ => return Err(bad(16)),
    };
    Ok(RollRecord {
        id: unsigned(0)?,
        initial,
        start_face: small(14)?.ok_or_else(|| bad(14))?,
        outcome: Outcome {
            status,
            face: small(15)?,
            steps: unsigned(17)?,
            time_s: required(18)?,
        },
    })
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
        let mut w = RecordsWriter::new(Vec::new(), "{}").unwrap();
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
        read_records(std::fs::File::open(&path).unwrap(), Some("{}"), &mut |r| {
            back.push(r);
            Ok(())
        })
        .unwrap();
        assert_eq!(back.len(), rs.len());
        for (a, b) in back.iter().zip(&rs) {
            assert_eq!(format!("{a:?}"), format!("{b:?}"));
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
                    read_records(file, None, &mut |_| Ok(()))
                }));
                assert!(read.is_ok(), "a flip of bit {bit} at byte {at} panicked");
            }
        }
    }
}
