"""The module's records are the command line's: same setup and seed, the same values to the
bit, whatever the threads or the engine."""

import csv
import json
import math
import pytest
import struct

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

import dicesim
from dicesim import _native

# A setup away from the paper's in a value of each kind: a loaded corner, a softer table,
# a narrower throw, so a module that dropped a change would give other rolls.
CHANGES = {
    "die.extra_corner_mass": [0, 0, 0, 0, 0, 0, 0, 0.3],
    "ground.damping": 0.004,
    "random.height": [10, 14],
}
SETS = [f"--set={key}={dicesim._toml_value(value)}" for key, value in CHANGES.items()]


def bits(values):
    """Floats as their 64-bit patterns (NaN-safe, -0.0 apart from 0.0)."""
    return np.asarray(values, dtype=np.float64).view(np.int64)


def test_a_batch_is_the_cli_parquet_file_byte_for_byte_and_its_csv_value_for_value(tmp_path, dicesim_cli):
    setup = dicesim.Setup(changes=CHANGES)
    dicesim_cli("batch", "--rolls", 1500, "--seed", 7, *SETS, "--out", tmp_path / "b.parquet")
    dicesim_cli("batch", "--rolls", 1500, "--seed", 7, *SETS, "--out", tmp_path / "b.csv")
    parquet, _columns, _report = _native.batch(setup._native, 1500, 7, 0, "auto")
    assert parquet == (tmp_path / "b.parquet").read_bytes()

    table = dicesim.batch(setup, rolls=1500, seed=7)
    assert table.num_rows == 1500
    assert table.equals(pq.read_table(tmp_path / "b.parquet"))
    # Every cell of the CSV: integers equal, reals bit for bit (the CSV prints them in
    # shortest round-trip form), empty cells null.
    sidecar = json.loads((tmp_path / "b.csv.meta.json").read_text())
    kinds = {c["name"]: c["type"] for c in sidecar["columns"]}
    with open(tmp_path / "b.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert table.column_names == list(rows[0])
    for name in table.column_names:
        got = table.column(name).to_pylist()
        cells = [r[name] for r in rows]
        if kinds[name] == "real":
            want = [float(c) if c else None for c in cells]
            assert [None if v is None else struct.pack("<d", v) for v in got] == [
                None if v is None else struct.pack("<d", v) for v in want
            ], name
        elif kinds[name] == "integer":
            assert got == [int(c) if c else None for c in cells], name
        else:
            assert got == [c if c else None for c in cells], name
    # The provenance is the file's, and names the setup changed.
    assert json.loads(table.schema.metadata[b"dicesim"]) == sidecar["provenance"]
    assert sidecar["provenance"]["preset"]["ground"]["damping"] == 0.004


def test_threads_and_engines_change_no_bit():
    setup = dicesim.Setup(changes=CHANGES)
    runs = [
        _native.batch(setup._native, 600, 3, jobs, engine)[0]
        for jobs, engine in [(1, "scalar"), (2, "lanes"), (0, "auto")]
    ]
    assert runs[0] == runs[1] == runs[2]


def test_the_report_is_batch_json(dicesim_cli):
    setup = dicesim.Setup(changes=CHANGES)
    table = dicesim.batch(setup, rolls=400, seed=2)
    report = json.loads(table.schema.metadata[b"dicesim-report"])
    cli = json.loads(dicesim_cli("batch", "--rolls", 400, "--seed", 2, *SETS, "--json").stdout)
    # The summary's timing is this run's own.
    for r in (report, cli):
        for timing in ("elapsed_s", "rolls_per_s", "steps_per_s"):
            r["summary"].pop(timing)
    assert report == cli
    faces = table.column("face").to_pylist()
    assert sum(report["summary"]["faces"]["counts"]) == sum(f is not None for f in faces)
    # One count per number the die shows, in its order: the cube's 1 to 6.
    assert setup.face_numbers == [1, 2, 3, 4, 5, 6]
    counts = report["summary"]["faces"]["counts"]
    assert counts == [faces.count(n) for n in setup.face_numbers]
    assert len(report["summary"]["face_shares"]) == len(setup.face_numbers)


def test_a_pandas_frame_carries_the_provenance():
    frame = dicesim.batch(rolls=50, seed=1, to="pandas")
    assert list(frame["id"]) == list(range(50))
    assert frame.attrs["provenance"]["seed"] == 1
    assert frame.attrs["report"]["completed"] == 50


def test_a_trace_is_dicesim_trace(tmp_path, dicesim_cli):
    setup = dicesim.Setup(changes={"initial.height": 6, "initial.angular_velocity": [3, -8, 1]})
    rows = dicesim_cli(
        "trace", "--every", 7, "--set", "initial.height=6", "--set", "initial.angular_velocity=[3, -8, 1]"
    ).stdout.splitlines()
    header, cells = rows[0].split(","), [r.split(",") for r in rows[1:]]
    trace = dicesim.trace(setup, every=7)
    assert list(trace) == header
    assert trace["step"].tolist() == [int(r[0]) for r in cells]
    for i, name in enumerate(header[1:], start=1):
        assert np.array_equal(bits(trace[name]), bits([float(r[i]) for r in cells])), name
    # Exactly N steps, as --steps.
    short = dicesim.trace(setup, steps=25, every=10)
    assert short["step"].tolist() == [0, 10, 20, 25]


def test_a_roll_is_roll_json(dicesim_cli):
    setup = dicesim.Setup("gentle-drop")
    setup["ground.friction"] = 0.4
    cli = json.loads(dicesim_cli("roll", "--preset", "gentle-drop", "--set", "ground.friction=0.4", "--json").stdout)
    assert dicesim.roll(setup) == cli


def test_a_map_is_the_cli_map_csv(tmp_path, dicesim_cli):
    x, y = "initial.angular_velocity.x:-40:40", "ground.friction:0.3:1.2"
    dicesim_cli("basin", "--x", x, "--y", y, "--res", "9x5", "--out", tmp_path / "m.csv")
    table = dicesim.basin(x=x, y=y, res=(9, 5))
    sidecar = json.loads((tmp_path / "m.csv.meta.json").read_text())
    assert json.loads(table.schema.metadata[b"dicesim"]) == sidecar["provenance"]
    with open(tmp_path / "m.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert table.num_rows == len(rows) == 45
    for column in sidecar["columns"]:
        name, got = column["name"], table.column(column["name"]).to_pylist()
        cells = [r[name] for r in rows]
        if column["type"] == "real":
            assert np.array_equal(bits(got), bits([float(c) for c in cells])), name
        elif column["type"] == "integer":
            assert got == [int(c) if c else None for c in cells], name
        else:
            assert got == cells, name


def test_a_comparison_is_compare_csv_and_json(tmp_path, dicesim_cli):
    dicesim_cli(
        "compare", "weldon", "--throws", 300, "--seed", 4, "--fit", "ground.friction:0.4:1.2",
        "--out", tmp_path / "c.csv", "--out", tmp_path / "c.json",
    )
    c = dicesim.compare(dataset="weldon", throws=300, seed=4, fit="ground.friction:0.4:1.2")
    assert c.result == json.loads((tmp_path / "c.json").read_text())
    assert c.result["fit"]["best"] is not None
    with open(tmp_path / "c.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    # A row per candidate and category: 21 candidates of Weldon's 8 pooled categories.
    assert c.table.num_rows == len(rows) == 21 * len(c.result["candidates"][0]["test"]["groups"])
    for name in c.table.column_names:
        got = c.table.column(name).to_pylist()
        cells = [r[name] for r in rows]
        for g, cell in zip(got, cells):
            if cell == "":
                assert g is None, name
            elif isinstance(g, float):
                assert struct.pack("<d", g) == struct.pack("<d", float(cell)), name
            elif isinstance(g, bool):
                assert str(g).lower() == cell, name
            else:
                assert str(g) == cell, name


def test_the_shaved_die_is_compare_shaved_die(tmp_path, dicesim_cli):
    dicesim_cli(
        "compare", "shaved-die", "--throws", 60, "--seed", 3, "--cuts", "0.03,0.2",
        "--out", tmp_path / "s.csv", "--out", tmp_path / "s.json",
    )
    c = dicesim.compare(dataset="shaved-die", throws=60, seed=3, cuts=[0.03, 0.2])
    assert c.result == json.loads((tmp_path / "s.json").read_text())
    # A row per cut; only the measured one (3 %) carries the data's bias.
    assert c.table.column("cut").to_pylist() == [0.03, 0.2]
    assert c.table.column("data_bias").to_pylist() == [0.06, None]
    with pytest.raises(ValueError, match="not for \"shaved-die\""):
        dicesim.compare(dataset="shaved-die", throws=5, fit="ground.friction:0.2:1")
    with pytest.raises(ValueError, match="is not one"):
        dicesim.compare("tennis-racket", "shaved-die", throws=5)


def test_budden_pools_seeds_as_the_cli_does(tmp_path, dicesim_cli):
    dicesim_cli(
        "compare", "budden", "--no-fit", "--throws", 40, "--seed", "11,12",
        "--out", tmp_path / "b.json",
    )
    c = dicesim.compare(dataset="budden", no_fit=True, throws=40, seed=[11, 12])
    assert c.result == json.loads((tmp_path / "b.json").read_text())
    assert c.table.column("ratio").to_pylist()[0] == 0.47
    assert math.isfinite(c.result["all"]["chi_square"])


def test_a_players_counts_are_compare_counts(tmp_path, dicesim_cli):
    counts = {face: 5 + (face * 7) % 11 for face in range(1, 21)}
    path = tmp_path / "d20.csv"
    path.write_text("# die: d20\nface,count\n" + "".join(f"{f},{n}\n" for f, n in counts.items()))
    dicesim_cli(
        "compare", "--counts", path, "--throws", 200, "--seed", 5,
        "--out", tmp_path / "k.csv", "--out", tmp_path / "k.json",
    )
    c = dicesim.compare(counts=path, throws=200, seed=5)
    assert c.result == json.loads((tmp_path / "k.json").read_text())
    # The same counts as a mapping, held against the d20 preset by name.
    by_mapping = dicesim.compare("d20", counts=counts, throws=200, seed=5)
    assert by_mapping.result["candidates"] == c.result["candidates"]
    assert c.result["data"]["counts"] == list(counts.values())
    assert c.result["fairness"]["die"] == "d20"
    # Faces too rare among the simulated rolls are pooled with their neighbours (the
    # comparison's groups): the rows still cover faces 1 to 20, each once, with every count.
    first = c.table.column("category_first").to_pylist()
    last = c.table.column("category_last").to_pylist()
    assert first[0] == 1 and last[-1] == 20
    assert all(f == l + 1 for f, l in zip(first[1:], last[:-1]))
    assert sum(c.table.column("data_count").to_pylist()) == sum(counts.values())
    with pytest.raises(ValueError, match="line 3: face 21"):
        bad = tmp_path / "bad.csv"
        bad.write_text("face,count\n1,5\n21,5\n")
        dicesim.compare("d20", counts=bad)
