"""docs/python.md's examples run as they stand and draw their figures."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT

EXAMPLES = re.findall(r"```python\n(.*?)```", (ROOT / "docs" / "python.md").read_text(), re.S)


def test_the_docs_have_three_examples():
    assert len(EXAMPLES) == 3


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda e: re.search(r'savefig\("([^"]+)"', e).group(1))
def test_an_example_runs_and_writes_its_figure(tmp_path, example):
    figure = re.search(r'savefig\("([^"]+)"', example).group(1)
    done = subprocess.run([sys.executable, "-c", example], cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    png = Path(tmp_path, figure).read_bytes()
    assert png.startswith(b"\x89PNG") and len(png) > 10_000
