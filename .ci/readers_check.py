"""Reads every CSV dicesim wrote into a folder with the four readers people use, each with no
option at all: pandas.read_csv(path), polars.read_csv(path), pyarrow.csv.read_csv(path) and
DuckDB's read_csv_auto(path). Each must find the same rows and columns, each column of the
type the file's sidecar (<file>.meta.json) states, and the same values, floats bit for bit:
the values of the Parquet file of the same records where there is one (NAME.parquet beside
NAME.csv), else the file's own cells read as the sidecar says.

The one type the readers cannot agree on is pandas' for a whole-number column with empty
cells (a face where a roll did not settle): numpy's integers have no missing value, so
pandas reads such a column as float64, its values still exactly the whole numbers.

Usage: python3 readers_check.py FOLDER
"""

import csv
import json
import math
import pathlib
import struct
import sys

import duckdb
import pandas
import polars
import pyarrow
import pyarrow.csv
import pyarrow.parquet

KINDS = ("integer", "real", "text", "boolean")


def same(a, b):
    """Whether two cell values are the same: floats bit for bit, None for a missing one."""
    if a is None or b is None:
        return a is None and b is None
    if isinstance(a, float) or isinstance(b, float):
        if not (isinstance(a, (int, float)) and isinstance(b, (int, float))):
            return False
        return struct.pack("<d", float(a)) == struct.pack("<d", float(b))
    return type(a) is type(b) and a == b


def from_text(cell, kind):
    """A cell of the CSV as the sidecar says its column holds (Python's float() is the
    correctly rounded reading of the shortest round-trip digits the program writes)."""
    if cell == "":
        return None
    if kind == "integer":
        return int(cell)
    if kind == "real":
        assert "." in cell or "e" in cell or cell in ("inf", "-inf", "NaN"), cell
        return float(cell)
    if kind == "boolean":
        assert cell in ("true", "false"), cell
        return cell == "true"
    return cell


def expected_table(path, columns):
    """The values the readers must find: the Parquet's, else the cells read as typed."""
    parquet = path.with_suffix(".parquet")
    if parquet.exists():
        table = pyarrow.parquet.read_table(parquet)
        assert table.column_names == [c["name"] for c in columns], (parquet, table.column_names)
        values = {n: table.column(n).to_pylist() for n in table.column_names}
        # The Parquet's integers are unsigned and narrow, its reals doubles: the same values.
        for c in columns:
            if c["kind"] == "real":
                values[c["name"]] = [None if v is None else float(v) for v in values[c["name"]]]
        return values, table.num_rows, "the Parquet"
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    assert header == [c["name"] for c in columns], (path, header)
    values = {c["name"]: [from_text(r[i], c["kind"]) for r in rows] for i, c in enumerate(columns)}
    return values, len(rows), "its cells read as its sidecar types them"


def kind_in(reader, dtype, has_nulls):
    """The kind a reader's column type is, as the sidecar names kinds."""
    text = str(dtype).lower()
    if reader == "pandas":
        kind = getattr(dtype, "kind", "")
        if kind in "iu":
            return "integer"
        if kind == "f":
            return "real"
        if kind == "b":
            return "boolean"
        if kind in "OU" or "str" in text:
            return "text"
    if reader == "polars":
        if dtype.is_integer():
            return "integer"
        if dtype.is_float():
            return "real"
        if dtype == polars.Boolean:
            return "boolean"
        if dtype == polars.String:
            return "text"
    if reader == "pyarrow":
        if pyarrow.types.is_integer(dtype):
            return "integer"
        if pyarrow.types.is_floating(dtype):
            return "real"
        if pyarrow.types.is_boolean(dtype):
            return "boolean"
        if pyarrow.types.is_string(dtype) or pyarrow.types.is_large_string(dtype):
            return "text"
    if reader == "duckdb":
        if text in ("tinyint", "smallint", "integer", "bigint", "hugeint", "ubigint", "uinteger"):
            return "integer"
        if text in ("double", "float"):
            return "real"
        if text == "boolean":
            return "boolean"
        if text == "varchar":
            return "text"
    return f"unknown ({dtype})"


def read_with(reader, path):
    """The file as `reader` reads it with no options: names, kinds, values per column."""
    if reader == "pandas":
        frame = pandas.read_csv(path)
        columns = list(frame.columns)
        kinds = [frame[c].dtype for c in columns]
        values = {
            c: [None if (isinstance(v, float) and math.isnan(v)) or v is pandas.NA or v is None else v.item() if hasattr(v, "item") else v for v in frame[c].tolist()]
            for c in columns
        }
        return columns, kinds, values, len(frame)
    if reader == "polars":
        frame = polars.read_csv(path)
        return frame.columns, list(frame.dtypes), {c: frame[c].to_list() for c in frame.columns}, frame.height
    if reader == "pyarrow":
        table = pyarrow.csv.read_csv(path)
        return (
            table.column_names,
            [f.type for f in table.schema],
            {c: table.column(c).to_pylist() for c in table.column_names},
            table.num_rows,
        )
    relation = duckdb.sql(f"SELECT * FROM read_csv_auto('{path}')")
    columns = relation.columns
    rows = relation.fetchall()
    values = {c: [r[i] for r in rows] for i, c in enumerate(columns)}
    return columns, relation.types, values, len(rows)


def check(path):
    sidecar = json.loads(pathlib.Path(str(path) + ".meta.json").read_text())
    columns = [{"name": c["name"], "kind": c["type"]} for c in sidecar["columns"]]
    assert all(c["kind"] in KINDS for c in columns), columns
    provenance = sidecar["provenance"]
    assert provenance["program"].startswith("dicesim "), provenance
    assert provenance["commit"], provenance
    expected, rows, reference = expected_table(path, columns)
    assert rows > 0, path
    for c in columns:
        assert any(v is not None for v in expected[c["name"]]), f"{path}: {c['name']} is empty in every row"
    for reader in ("pandas", "polars", "pyarrow", "duckdb"):
        names, dtypes, values, n = read_with(reader, path)
        where = f"{path.name}, {reader}"
        assert list(names) == [c["name"] for c in columns], (where, names)
        assert n == rows, (where, n, rows)
        for c, dtype in zip(columns, dtypes):
            name, kind = c["name"], c["kind"]
            has_nulls = any(v is None for v in expected[name])
            found = kind_in(reader, dtype, has_nulls)
            pandas_integer_with_gaps = reader == "pandas" and kind == "integer" and has_nulls and found == "real"
            assert found == kind or pandas_integer_with_gaps, (where, name, kind, str(dtype))
            for r, (a, b) in enumerate(zip(values[name], expected[name])):
                if pandas_integer_with_gaps and a is not None:
                    assert a == int(a), (where, name, r, a)
                    a = int(a)
                assert same(a, b), (where, name, r, a, b)
    return f"{path.name}: {rows} rows x {len(columns)} columns, as {reference}"


def main(folder):
    files = sorted(pathlib.Path(folder).glob("*.csv"))
    assert files, folder
    for path in files:
        print("readers:", check(path))
    print(
        f"readers: pandas {pandas.__version__}, polars {polars.__version__}, pyarrow {pyarrow.__version__}, "
        f"duckdb {duckdb.__version__} read {len(files)} files alike"
    )


if __name__ == "__main__":
    main(*sys.argv[1:])
