"""The Python examples of README.md and docs/python.md run, and print the figures they quote."""

import math
import re

import numpy as np

import deb
from conftest import SOURCE_DIR


def python_blocks(markdown):
    return re.findall(r"```python\n(.*?)```", markdown, re.DOTALL)


def test_the_documented_examples_run(monkeypatch, capsys):
    monkeypatch.chdir(SOURCE_DIR)  # they name budgets/... from the checkout
    for page in ("README.md", "docs/python.md"):
        blocks = python_blocks((SOURCE_DIR / page).read_text())
        assert blocks
        namespace = {}  # a page's blocks follow on from each other
        for block in blocks:
            exec(compile(block, page, "exec"), namespace)
    capsys.readouterr()


def test_the_quoted_figures_hold():
    readme = (SOURCE_DIR / "README.md").read_text()
    python_md = (SOURCE_DIR / "docs" / "python.md").read_text()
    thesis = SOURCE_DIR / "budgets" / "nizamoglu2015_h210.yaml"
    z = deb.evaluate(deb.load(thesis, set={"Kv": 100})).output("z_position")
    assert f"{z.rms:.4g} {z.unit}" in readme  # 2.709 um
    r = deb.evaluate(SOURCE_DIR / "budgets" / "guide" / "first_budget.yaml")
    t = r.output("table_z")
    assert f"{t.rms:.4g} nm, False" in python_md and not t.passed
    assert f"{math.sqrt(t.cps[np.searchsorted(r.f, 10.0)]):.4g} nm" in python_md
