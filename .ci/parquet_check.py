"""Reads a batch's Parquet with pyarrow (a client that is not dicesim's own) and checks
that every column equals the same batch's CSV, cell for cell and bit for bit, and that the
file's key-value metadata carries the provenance the CSV's first line carries.

Usage: python3 parquet_check.py BATCH.parquet BATCH.csv
"""

import csv
import json
import math
import struct
import sys

import pyarrow
import pyarrow.parquet as pq


def bits(x):
    return struct.pack("<d", x)


def main(parquet_path, csv_path):
    table = pq.read_table(parquet_path)
    with open(csv_path, newline="") as f:
        provenance_line = f.readline()
        assert provenance_line.startswith("# "), "the CSV starts with its provenance"
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    assert table.column_names == header, (table.column_names, header)
    assert table.num_rows == len(rows), (table.num_rows, len(rows))
    for i, name in enumerate(header):
        column = table.column(name).to_pylist()
        for r, (value, cell) in enumerate(zip(column, (row[i] for row in rows))):
            if value is None:
                assert cell == "", (name, r, value, cell)
            elif isinstance(value, float):
                # The CSV writes the shortest text that reads back to the same double.
                assert bits(value) == bits(float(cell)), (name, r, value, cell)
                assert math.isfinite(value), (name, r, value)
            else:
                assert str(value) == cell, (name, r, value, cell)
    metadata = table.schema.metadata or {}
    stored = metadata.get(b"dicesim")
    assert stored is not None, "the Parquet file carries its provenance"
    provenance = json.loads(stored)
    assert provenance == json.loads(provenance_line[2:]), "one provenance in both files"
    assert provenance["program"].startswith("dicesim "), provenance
    assert provenance["rolls"] == table.num_rows, provenance
    assert "preset" in provenance and "seed" in provenance, provenance
    print(
        f"parquet: pyarrow {pyarrow.__version__} read {table.num_rows} rows x {len(header)} columns "
        f"equal to the CSV; provenance {provenance['program']}, seed {provenance['seed']}"
    )


if __name__ == "__main__":
    main(*sys.argv[1:])
