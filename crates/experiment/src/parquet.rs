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

use crate::columns::{Cell, RecordColumn, SpinColumns, Type, record_from_cells};
use crate::record::RollRecord;
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
    let fields: Vec<String> = (spin.columns().iter())
        .map(|c| {
            let repetition = if c.nullable(spin) { "OPTIONAL" } else { "REQUIRED" };
            format!("{repetition} {};", c.ty.parquet(c.name()))
        })
        .collect();
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
        let mut columns = self.spin.columns().iter();
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

/// Writes `column` of `rows`: the values present, and where the column may be empty which
/// rows have one.
fn write_column(
    w: &mut parquet::file::writer::SerializedColumnWriter<'_>,
    column: &RecordColumn,
    spin: SpinColumns,
    rows: &[RollRecord],
) -> Result<(), ParquetError> {
    let cells: Vec<Cell<'static>> = rows.iter().map(|r| (column.get)(r)).collect();
    let levels: Option<Vec<i16>> = (column.nullable(spin)).then(|| {
        (cells.iter())
            .map(|c| i16::from(!matches!(c, Cell::Empty)))
            .collect()
    });
    let levels = levels.as_deref();
    match column.ty {
        Type::Count => {
            let values: Vec<i64> = cells.iter().filter_map(|c| c.whole()).map(|n| n as i64).collect();
            w.typed::<Int64Type>().write_batch(&values, levels, None)?;
        }
        Type::Face => {
            let values: Vec<i32> = cells.iter().filter_map(|c| c.small()).map(i32::from).collect();
            w.typed::<Int32Type>().write_batch(&values, levels, None)?;
        }
        Type::Real => {
            let values: Vec<f64> = cells.iter().filter_map(|c| c.real()).collect();
            w.typed::<DoubleType>().write_batch(&values, levels, None)?;
        }
        Type::Word => {
            let values: Vec<ByteArray> = (cells.iter())
                .filter_map(|c| match c {
                    Cell::Word(w) => Some(ByteArray::from(*w)),
                    _ => None,
                })
                .collect();
            w.typed::<ByteArrayType>().write_batch(&values, levels, None)?;
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
    let columns = layout.columns();
    let mut rows = untrusted(|| reader.get_row_iter(None).map_err(|e| e.to_string()))?;
    while let Some(row) = untrusted(|| Ok(rows.next()))? {
        let row = row.map_err(|e| e.to_string())?;
        let fields: Vec<&Field> = row.get_column_iter().map(|(_, f)| f).collect();
        each(record_from(columns, &fields)?)?;
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
    let layout = SpinColumns::ALL
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
fn record_from(columns: &[&RecordColumn], f: &[&Field]) -> Result<RollRecord, String> {
    if f.len() != columns.len() {
        return Err(format!("a row of {} fields, expected {}", f.len(), columns.len()));
    }
    let bad = |i: usize| format!("column {i} holds an unexpected value {:?}", f[i]);
    let cells = (f.iter().zip(columns).enumerate())
        .map(|(i, (field, column))| match (column.ty, field) {
            (_, Field::Null) => Ok(Cell::Empty),
            (Type::Count, Field::ULong(v)) => Ok(Cell::Whole(*v)),
            (Type::Face, Field::UByte(v)) => Ok(Cell::Whole(u64::from(*v))),
            (Type::Real, Field::Double(v)) => Ok(Cell::Real(*v)),
            (Type::Word, Field::Str(s)) => Ok(Cell::Word(s.as_str())),
            _ => Err(bad(i)),
        })
        .collect::<Result<Vec<Cell<'_>>, String>>()?;
    record_from_cells(columns, &cells, None)
        .map_err(|(i, why)| format!("column {i} (`{}`) {why}", columns[i].name()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::RandomRanges;
    use crate::record::roll_record;
    use dicesim_physics::{InitialCondition, Params, Status};
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
            assert!(crate::columns::same_record(a, b), "{a:?} {b:?}");
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
