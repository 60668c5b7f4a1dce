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


def _the_cli_blas_kernels():
    """This process loads OpenBLAS with the kernels the CLI uses.

    Where OpenBLAS picks kernels older than the processor runs, the CLI
    starts itself again with OPENBLAS_CORETYPE set (`deb --version` names
    the kernels); this module cannot, and without the same kernels the
    results that go through LAPACK differ from the CLI's in their last
    digits. Set here, at the suite's start, before numpy loads OpenBLAS;
    so is one thread per call, as the CLI runs OpenBLAS
    (deb::UseOneBlasThreadPerCall), whose products round alike only on
    the same threads.
    """
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    if "OPENBLAS_CORETYPE" in os.environ:
        return
    version = subprocess.run([deb_binary(), "--version"], capture_output=True, text=True, check=True).stdout
    prefix, suffix = "BLAS: OpenBLAS, ", " kernels"
    for line in version.splitlines():
        if line.startswith(prefix) and line.endswith(suffix):
            os.environ["OPENBLAS_CORETYPE"] = line[len(prefix):-len(suffix)]


_the_cli_blas_kernels()


@pytest.fixture
def source_dir():
    return SOURCE_DIR
