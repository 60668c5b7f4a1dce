"""The pytest suite of the Python module deb (CTest `python`, python/CMakeLists.txt).

Run by CTest with PYTHONPATH=build/python and DEB_BINARY=build/bin/deb; by
hand: PYTHONPATH=build/python DEB_BINARY=build/bin/deb /usr/bin/python3 -m pytest python/tests
"""

import json
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
BUDGETS = SOURCE_DIR / "budgets"


def deb_binary():
    return os.environ.get("DEB_BINARY", str(SOURCE_DIR / "build" / "bin" / "deb"))


def cli_summary(budget, out_dir, *args):
    """summary.json of `deb run --no-plots` on `budget` (with extra CLI arguments), as a dict."""
    subprocess.run([deb_binary(), "run", str(budget), "--no-plots", "--quiet", "--out", str(out_dir), *args],
                   check=True, stdout=subprocess.DEVNULL)
    with open(pathlib.Path(out_dir) / "summary.json", encoding="utf-8") as f:
        return json.load(f)


@pytest.fixture
def source_dir():
    return SOURCE_DIR
