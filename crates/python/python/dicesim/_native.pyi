"""Type stubs of the extension module; the documented API is `dicesim` (``__init__.py``)."""

from typing import Any, Dict, List, Optional, Tuple

VERSION: str
PROGRAM: str

class Setup:
    """A preset and the changes made to it, as ``--set KEY=VALUE`` makes them."""

    def __init__(self, preset: Optional[str] = None) -> None: ...
    @staticmethod
    def from_toml(text: str, origin: str = "<string>") -> "Setup": ...
    @property
    def name(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def changes(self) -> List[str]: ...
    def set_text(self, key: str, value: str) -> None:
        """Applies ``key=value`` (``value`` in ``--set``'s TOML form); raises ValueError."""
    def get(self, key: str) -> Any: ...
    @staticmethod
    def keys() -> List[str]: ...
    @staticmethod
    def describe(key: str) -> Dict[str, Any]: ...
    def to_toml(self) -> str: ...
    def save(self, path: str, force: bool = False) -> None: ...
    def copy(self) -> "Setup": ...

def preset_names() -> List[str]: ...
def roll(setup: Setup) -> str:
    """``dicesim roll --json``'s text."""

def trace(setup: Setup, steps: Optional[int] = None, every: int = 1) -> Tuple[List[str], bytes, bytes]:
    """The column names, the steps (native-endian u64) and the other columns' values
    (native-endian f64, row by row)."""

def batch(setup: Setup, rolls: int, seed: Optional[int] = None, jobs: int = 0, engine: str = "auto") -> Tuple[bytes, str, str]:
    """The Parquet file ``batch --out`` writes, its columns (JSON) and ``batch --json``'s report."""

def basin(
    setup: Setup,
    x: str,
    y: str,
    res: Tuple[int, int] = (200, 100),
    method: Optional[str] = None,
    jobs: int = 0,
    engine: str = "auto",
) -> Tuple[bytes, str, str]:
    """The CSV ``basin --out map.csv`` writes, its columns (JSON) and a report: the map's
    provenance, its method and whether it is complete."""

def compare(
    setup: Setup,
    dataset: str,
    throws: Optional[int] = None,
    seeds: List[int] = ...,
    fit: Optional[str] = None,
    no_fit: bool = False,
    candidates: Optional[int] = None,
    calibrate_on: Optional[List[float]] = None,
    jobs: int = 0,
    engine: str = "auto",
    cuts: Optional[List[float]] = None,
) -> Tuple[bytes, str, str]:
    """The CSV ``compare --out FILE.csv`` writes, its columns (JSON) and the result
    ``--out FILE.json`` holds (with its provenance)."""

def compare_counts(
    setup: Optional[Setup],
    counts: str,
    throws: Optional[int] = None,
    seed: Optional[int] = None,
    fit: Optional[str] = None,
    candidates: Optional[int] = None,
    jobs: int = 0,
    engine: str = "auto",
) -> Tuple[bytes, str, str]:
    """The CSV ``compare --counts COUNTS --out FILE.csv`` writes, its columns (JSON) and the
    result ``--out FILE.json`` holds (with its provenance); no setup: the shipped preset of
    the die the counts name."""
