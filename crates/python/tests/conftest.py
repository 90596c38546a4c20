"""What every test of the Python module shares: the command line it is held against."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def dicesim_cli():
    """Runs the command line built from the same tree (`.ci/python` names it in DICESIM_CLI)
    and returns the finished process; a failure keeps its status and stderr for the test."""
    exe = os.environ.get("DICESIM_CLI") or str(ROOT / "target" / "release" / "dicesim")
    if not Path(exe).is_file():
        pytest.fail(f"no dicesim binary at {exe}: build it, or set DICESIM_CLI")

    def run(*args, check=True):
        done = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
        if check and done.returncode != 0:
            raise AssertionError(f"dicesim {' '.join(map(str, args))}: {done.stderr}")
        return done

    return run
