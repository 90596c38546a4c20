//! A CSV file as every reader takes it, with no options: its first line is its header, each
//! numeric column is named with its unit, each column holds one type in every row (reals
//! written as reals, [`Real`](dicesim_setup::number::Real)) and none is empty in every row.
//! What a CSV cannot hold goes into its sidecar `<file>.meta.json` (see
//! [`dicesim_setup::output`]): the provenance, and each column's name and type.

use serde::Serialize;
use serde_json::Value;

/// The sidecar's format; a reader refuses a newer one.
pub const SIDECAR_FORMAT: u32 = 1;

/// The type of a column, as the sidecar states it and every reader should find it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// Whole numbers (ids, counts, faces, steps); an empty cell where there is no value.
    Integer,
    /// Reals, always with a decimal point or an exponent.
    Real,
    /// Words (a status, a role).
    Text,
    /// `true` or `false`.
    Boolean,
}

/// One column of a CSV file.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Column {
    pub name: String,
    #[serde(rename = "type")]
    pub kind: Kind,
}

impl Column {
    pub fn integer(name: impl Into<String>) -> Column {
        Column {
            name: name.into(),
            kind: Kind::Integer,
        }
    }

    pub fn real(name: impl Into<String>) -> Column {
        Column {
            name: name.into(),
            kind: Kind::Real,
        }
    }

    pub fn text(name: impl Into<String>) -> Column {
        Column {
            name: name.into(),
            kind: Kind::Text,
        }
    }

    pub fn boolean(name: impl Into<String>) -> Column {
        Column {
            name: name.into(),
            kind: Kind::Boolean,
        }
    }
}

/// The header line of a CSV with `columns` (names are plain words: never quoted).
pub fn header(columns: &[Column]) -> String {
    columns
        .iter()
        .map(|c| c.name.as_str())
        .collect::<Vec<_>>()
        .join(",")
}

#[derive(Serialize)]
struct Sidecar<'a> {
    format: u32,
    provenance: &'a Value,
    columns: &'a [Column],
}

/// The bytes of the sidecar of a CSV with `columns` that came from `provenance`: one JSON
/// object, `{"format", "provenance", "columns": [{"name", "type"}, …]}`, written the same for
/// the same file on any machine (a merge compares it byte for byte).
pub fn sidecar(provenance: &Value, columns: &[Column]) -> Vec<u8> {
    let mut bytes = serde_json::to_vec_pretty(&Sidecar {
        format: SIDECAR_FORMAT,
        provenance,
        columns,
    })
    .expect("a provenance always serialises");
    bytes.push(b'\n');
    bytes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sidecar_holds_the_provenance_and_every_columns_type() {
        let columns = [
            Column::integer("id"),
            Column::real("height_cm"),
            Column::text("status"),
        ];
        assert_eq!(header(&columns), "id,height_cm,status");
        let bytes = sidecar(&serde_json::json!({"seed": 3}), &columns);
        let back: Value = serde_json::from_slice(&bytes).unwrap();
        assert_eq!(back["format"], SIDECAR_FORMAT);
        assert_eq!(back["provenance"]["seed"], 3);
        assert_eq!(back["columns"][1]["name"], "height_cm");
        assert_eq!(back["columns"][1]["type"], "real");
        assert_eq!(back["columns"][2]["type"], "text");
        assert!(bytes.ends_with(b"}\n"));
    }
}
