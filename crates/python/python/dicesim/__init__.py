"""dicesim from Python: a die rolling on a table as a rigid body.

The model of Chin & Li (2019): eight corner point masses moved as one rigid body on a stiff,
damped spring table with friction, stepped by semi-implicit Euler. Units are CGS throughout
(cm, g, s; forces in dyn, energies in erg, angles in rad unless a key says deg).

This module is the command line's engine, not a copy of it: a :class:`Setup` takes the same
keys, units, ranges and error messages as ``--set``, and :func:`batch`, :func:`basin` and
:func:`compare` return the very records ``dicesim batch``, ``basin`` and ``compare`` write
(same seed, same setup: the same bits), as pyarrow tables (or pandas DataFrames) whose
metadata carries the provenance. Long runs use every core with the GIL released and stop
on Ctrl-C (``KeyboardInterrupt``) within a fraction of a second.

    >>> import dicesim
    >>> table = dicesim.Setup("paper")
    >>> table["ground.damping"] = 0.01          # s/cm, checked against its range
    >>> rolls = dicesim.batch(table, rolls=10_000, seed=7)
    >>> rolls.column("face").to_pylist()[:5]
"""

from __future__ import annotations

import io
import json
import numbers
import os
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import pyarrow as pa
import pyarrow.csv as pa_csv
import pyarrow.parquet as pq

from . import _native

__all__ = [
    "Setup",
    "Comparison",
    "presets",
    "roll",
    "trace",
    "batch",
    "basin",
    "compare",
    "PROGRAM",
]

#: The program and version that rolls, as every file's provenance names it.
PROGRAM: str = _native.PROGRAM
__version__: str = PROGRAM.split()[-1]

#: Where a table's metadata keeps the provenance (the key the Parquet files use) and the
#: run's report (what the command's ``--json`` prints).
PROVENANCE_KEY = b"dicesim"
REPORT_KEY = b"dicesim-report"

_ARROW_TYPES = {"integer": pa.int64(), "real": pa.float64(), "text": pa.string(), "boolean": pa.bool_()}


def _toml_value(value: Any) -> str:
    """A Python value as ``--set`` takes it: numbers in shortest round-trip form (so the
    setup holds the very float given), lists as ``[a, b, c]``, flags as ``true``/``false``
    and names as they are."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    if isinstance(value, str):
        return value
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise TypeError(f"a setup value is a number, a list of numbers, a flag or a name, not {type(value).__name__}")


class Setup:
    """A preset and the changes made to it: everything one roll or experiment starts from.

    ``Setup()`` is the paper's setup; ``Setup("icy-table")`` a preset by name (your preset
    folder first, then the shipped ones, see :func:`presets`) or by path to a ``.toml`` file.
    ``changes`` applies ``{key: value}`` in order, as ``--set KEY=VALUE`` does.

    Read and change values by their preset keys, with the units of :meth:`describe`::

        s = Setup()
        s["ground.friction"]            # 1.2 (dimensionless)
        s["initial.angular_velocity"]   # [12.0, -20.0, 6.0] rad/s
        s["initial.velocity.y"] = 25    # one component, cm/s
        s["ground.friction"] = 9        # ValueError: `ground.friction` = 9 is outside the allowed range 0 to 5

    A change that fails raises ``ValueError`` with the command line's message and changes
    nothing. A run refuses a change it would not apply (``batch`` draws ``initial.height``
    from ``random.height``, say), as the command line refuses such a ``--set``.
    """

    __slots__ = ("_native",)

    def __init__(self, preset: Optional[str] = None, changes: Optional[Mapping[str, Any]] = None) -> None:
        self._native = _native.Setup(None if preset is None else str(preset))
        for key, value in (changes or {}).items():
            self[key] = value

    @classmethod
    def from_toml(cls, text: str, origin: str = "<string>") -> "Setup":
        """A setup from a preset file's text; ``origin`` names it in errors (file:line)."""
        setup = cls.__new__(cls)
        setup._native = _native.Setup.from_toml(text, origin)
        return setup

    @property
    def name(self) -> str:
        """The preset's name."""
        return self._native.name

    @property
    def description(self) -> str:
        """The preset's description."""
        return self._native.description

    @property
    def face_numbers(self) -> List[int]:
        """The numbers a roll of this setup's die can show (1 to 6 on the paper's cube), in
        the order a batch's ``summary["faces"]["counts"]`` and ``face_shares`` list them."""
        return self._native.face_numbers

    @property
    def changes(self) -> List[str]:
        """The changes made since the preset was loaded, as ``KEY=VALUE``, in order."""
        return self._native.changes

    def __getitem__(self, key: str) -> Any:
        return self._native.get(key)

    def __setitem__(self, key: str, value: Any) -> None:
        self._native.set_text(key, _toml_value(value))

    def with_values(self, values: Mapping[str, Any]) -> "Setup":
        """A copy with ``values`` (``{key: value}``) set, this setup unchanged: one line per
        candidate of a sweep or fit."""
        copy = self.copy()
        for key, value in values.items():
            copy[key] = value
        return copy

    def copy(self) -> "Setup":
        """An independent copy."""
        copy = Setup.__new__(Setup)
        # The copy keeps the changes it was made with, so a run refuses the same ones.
        copy._native = self._native.copy()
        return copy

    @staticmethod
    def keys() -> List[str]:
        """Every preset key, in the order a preset file lists them."""
        return _native.Setup.keys()

    @staticmethod
    def describe(key: str) -> Dict[str, Any]:
        """A key's registry row: ``unit``, ``min`` and ``max`` (numbers), ``choices``
        (names), ``default`` and ``meaning``."""
        return _native.Setup.describe(key)

    def to_toml(self) -> str:
        """The setup as a preset file, every value with its comment."""
        return self._native.to_toml()

    def save(self, path: str, force: bool = False) -> None:
        """Writes the setup as a preset file (``.toml``), whole or not at all; an existing
        file is replaced only with ``force=True`` (else ``FileExistsError``)."""
        self._native.save(str(path), force)

    def __repr__(self) -> str:
        return repr(self._native)


def presets() -> List[str]:
    """The names of the shipped presets (``Setup(name)`` loads one)."""
    return _native.preset_names()


def _setup(setup: Optional[Union[Setup, str]]) -> Any:
    if setup is None:
        return Setup()._native
    if isinstance(setup, str):
        return Setup(setup)._native
    if isinstance(setup, Setup):
        return setup._native
    raise TypeError(f"setup is a dicesim.Setup, a preset name or None, not {type(setup).__name__}")


def _table(table: pa.Table, report: Mapping[str, Any], to: str) -> Any:
    """``table`` with the provenance and the report in its metadata, as ``to`` asks."""
    metadata = dict(table.schema.metadata or {})
    metadata[PROVENANCE_KEY] = json.dumps(report["provenance"]).encode()
    metadata[REPORT_KEY] = json.dumps(report).encode()
    table = table.replace_schema_metadata(metadata)
    if to == "arrow":
        return table
    if to == "pandas":
        frame = table.to_pandas()
        frame.attrs["provenance"] = report["provenance"]
        frame.attrs["report"] = dict(report)
        return frame
    raise ValueError(f'to={to!r}: expected "arrow" or "pandas"')


def _csv_table(data: bytes, columns_json: str) -> pa.Table:
    """A CSV the program wrote, read with the types its sidecar states."""
    columns = json.loads(columns_json)
    types = {c["name"]: _ARROW_TYPES[c["type"]] for c in columns}
    return pa_csv.read_csv(
        io.BytesIO(data),
        convert_options=pa_csv.ConvertOptions(column_types=types, strings_can_be_null=False),
    )


def roll(setup: Optional[Union[Setup, str]] = None) -> Dict[str, Any]:
    """One roll of the setup's initial condition (``initial.*``) to its end.

    Returns what ``dicesim roll --json`` prints: ``face`` (one of ``setup.face_numbers``,
    or None), ``status``
    (``settled``, ``timeout``, ``unstable``), ``steps``, ``time_s`` (simulated s), the
    stopping rule's energies (erg), the stability check, the ``final`` state (position cm,
    velocity cm/s, angular momentum g·cm²/s, angular velocity rad/s, energies erg), the
    ``params``, the ``initial`` condition and the ``provenance``.
    """
    return json.loads(_native.roll(_setup(setup)))


def trace(
    setup: Optional[Union[Setup, str]] = None, steps: Optional[int] = None, every: int = 1
) -> Dict[str, np.ndarray]:
    """One roll's trajectory and energies, step by step: the columns of ``dicesim trace``.

    ``steps``: run exactly this many steps (default: until the roll ends); ``every``: keep
    one row every K steps (the last is always kept). Returns ``{column: array}``: ``step``
    (int64), ``time_s`` (s), the centre of mass ``x_cm``…, its velocity ``vx_cm_per_s``…, the
    angular momentum ``Lx_g_cm2_per_s``… and velocity ``wx_rad_per_s``…, the energies
    (``*_erg``: translational, rotational, gravitational, elastic, total) and every other
    quantity, then the corners ``c1x_cm`` … ``c8z_cm``; each value bit for bit the CSV's.
    """
    names, step_bytes, value_bytes = _native.trace(_setup(setup), steps, every)
    step = np.frombuffer(step_bytes, dtype=np.uint64).astype(np.int64)
    values = np.frombuffer(value_bytes, dtype=np.float64).reshape(len(step), len(names) - 1)
    columns: Dict[str, np.ndarray] = {names[0]: step}
    for i, name in enumerate(names[1:]):
        columns[name] = values[:, i].copy()
    return columns


def batch(
    setup: Optional[Union[Setup, str]] = None,
    rolls: int = 1000,
    seed: Optional[int] = None,
    jobs: int = 0,
    engine: str = "auto",
    to: str = "arrow",
) -> Any:
    """Rolls ``rolls`` dice, each start drawn from the setup's random ranges (``random.*``)
    with ``seed`` (default: ``random.seed``): roll i's start depends on (seed, i) alone.

    Returns the records ``dicesim batch --seed S --rolls N --out FILE.parquet`` writes,
    value for value and bit for bit: one row per roll with its ``id``, start
    (``height_cm``, ``velocity_*_cm_per_s``, ``angular_velocity_*_rad_per_s``, ``yaw_deg``,
    ``pitch_deg``, ``roll_deg``), ``start_face``, ``face`` (one of ``setup.face_numbers``,
    null if none), ``status``,
    ``steps``, ``time_s`` (simulated s) and its bounces (``impacts``,
    ``first_impact_steps``, ``first_impact_time_s``, ``first_impact_face_down``).
    ``to="arrow"``: a ``pyarrow.Table`` whose schema metadata
    holds the provenance (``b"dicesim"``) and the run's report (``b"dicesim-report"``: the
    summary ``dicesim batch --json`` prints, its face counts, shares and intervals one per
    number of ``setup.face_numbers``, in that order); ``to="pandas"``: a DataFrame with both
    in ``.attrs``.

    ``jobs``: worker threads (0: one per core); ``engine``: ``"auto"``, ``"scalar"`` or
    ``"lanes"``. Neither changes a bit of the result. The GIL is released while the dice
    roll; Ctrl-C stops every worker and raises ``KeyboardInterrupt``.
    """
    parquet, _columns, report = _native.batch(_setup(setup), int(rolls), seed, int(jobs), engine)
    # ParquetFile reads the one file as it is; read_table would first load pyarrow's
    # dataset machinery, a third of a second on a 100 000-roll batch's first call.
    return _table(pq.ParquetFile(pa.BufferReader(parquet)).read(), json.loads(report), to)


def basin(
    setup: Optional[Union[Setup, str]] = None,
    x: str = "initial.angular_velocity.x:-60:60",
    y: str = "initial.angular_velocity.y:-60:60",
    res: Tuple[int, int] = (200, 100),
    method: Optional[str] = None,
    jobs: int = 0,
    engine: str = "auto",
    to: str = "arrow",
) -> Any:
    """The ending over a grid of two setup values (a basin map), the setup's own start in
    every cell but for the two values.

    ``x`` and ``y``: ``"KEY:MIN:MAX"`` of any numeric key (a vector's component by its own
    key), ``res``: nodes along x and y, both ends included (``(W, 1)``: a 1-D scan);
    ``method``: ``"adaptive"`` (roll a coarse grid, then where neighbours differ; the
    default for 2-D maps) or ``"uniform"`` (every cell; the default for scans).

    Returns the rows of ``dicesim basin --out map.csv``: ``i``, ``j``, both values (named
    with their units), ``start_face``, ``face``, ``status``, ``steps``, ``time_s`` and
    ``sampled`` (1: rolled, 0: filled by the adaptive method), with the provenance in the
    metadata as for :func:`batch`.
    """
    data, columns, report = _native.basin(_setup(setup), x, y, tuple(res), method, int(jobs), engine)
    return _table(_csv_table(data, columns), json.loads(report), to)


@dataclass(frozen=True)
class Comparison:
    """A comparison with real dice: ``table``, the rows of ``dicesim compare --out FILE.csv``
    (provenance in its metadata), and ``result``, what ``--out FILE.json`` holds: the
    counts, χ², residuals, power and, with a fit, every candidate and the best value."""

    table: Any
    result: Dict[str, Any]


def compare(
    setup: Optional[Union[Setup, str]] = None,
    dataset: str = "weldon",
    throws: Optional[int] = None,
    seed: Optional[Union[int, Sequence[int]]] = None,
    fit: Optional[str] = None,
    no_fit: bool = False,
    candidates: Optional[int] = None,
    calibrate_on: Optional[Sequence[float]] = None,
    jobs: int = 0,
    engine: str = "auto",
    to: str = "arrow",
    cuts: Optional[Sequence[float]] = None,
    counts: Optional[Union[str, "os.PathLike[str]", Mapping[int, int]]] = None,
) -> Comparison:
    """Throws the setup's die as a historical experiment threw real dice and holds it
    against their counts: ``"weldon"`` (26 306 throws of 12 dice, 1894), ``"wolf-red"``,
    ``"wolf-white"`` (20 000 throws each, about 1850), ``"budden"`` (steel cuboids of 15
    ratios x/y, 1980) or ``"shaved-die"`` (a die cut along its 1–6 axis, 2001: each of
    ``cuts``, default 0.015, 0.03, 0.06, thrown with the uncut die over the same throws).

    ``throws``: simulated throws (default: as many as the experiment made); ``seed``: of
    the throws (default ``random.seed``; Budden pools several, e.g. ``[11, 12, 13]``);
    ``fit="KEY:LO:HI"``: fit one setup value, ``candidates`` values evenly spaced (at least
    20, default 21), each rolled with the same throws. Budden fits ``ground.damping`` on the
    ``calibrate_on`` ratios (default 0.63, 1.16, 1.87) unless ``no_fit=True`` and predicts
    the others out of sample. The same as ``dicesim compare`` with the same options.

    ``counts``: your own counts of a die's faces instead of an experiment ("Is my die
    fair?", ``dicesim compare --counts``): a ``{face: count}`` mapping, ``"1=12,2=9,…"``,
    or the path of a CSV file of ``face,count`` rows (``# die: d20`` names the die). The die
    is the setup's; with no setup, the shipped preset of the die a file names. The result
    adds ``fairness``: the verdict against a fair die, each face's residual, the simulated
    die against a fair one and the rolls a player needs to detect its flaw.
    """
    seeds: List[int] = [] if seed is None else ([int(seed)] if isinstance(seed, numbers.Integral) else [int(s) for s in seed])
    if counts is not None:
        if dataset != "weldon" or no_fit or calibrate_on is not None or cuts is not None:
            raise ValueError("counts are compared on their own: give no dataset, no_fit, calibrate_on or cuts with them")
        if len(seeds) > 1:
            raise ValueError("seed: several seeds are pooled for \"budden\" only; give one")
        if isinstance(counts, Mapping):
            text = ",".join(f"{int(face)}={int(n)}" for face, n in counts.items())
        else:
            text = os.fspath(counts)
        data, columns, result = _native.compare_counts(
            None if setup is None else _setup(setup),
            text,
            throws,
            seeds[0] if seeds else None,
            fit,
            candidates,
            int(jobs),
            engine,
        )
        result = json.loads(result)
        return Comparison(table=_table(_csv_table(data, columns), result, to), result=result)
    data, columns, result = _native.compare(
        _setup(setup),
        dataset,
        throws,
        seeds,
        fit,
        no_fit,
        candidates,
        None if calibrate_on is None else [float(r) for r in calibrate_on],
        int(jobs),
        engine,
        None if cuts is None else [float(c) for c in cuts],
    )
    result = json.loads(result)
    return Comparison(table=_table(_csv_table(data, columns), result, to), result=result)
