"""Bad input raises deb.InputError, located, and never crashes the interpreter."""

import subprocess
import sys

import numpy as np
import pytest

import deb
from test_modal import single_mode_budget


def test_a_negative_damping_is_located_at_its_key_and_line():
    b = single_mode_budget(zeta=-0.02)
    with pytest.raises(deb.InputError) as e:
        deb.load(b)
    err = e.value
    assert isinstance(err, ValueError)
    assert err.key_path == "paths[0].damping"
    assert err.file == "<dict>"
    # The line of `damping:` in the YAML text the dict was written as.
    lines = deb._yaml.dump(b).splitlines()
    assert lines[err.line - 1].strip().startswith("damping:")
    assert err.column is not None and err.column > 0
    assert str(err).startswith(f"<dict>:{err.line}:{err.column}: paths[0].damping: ")
    assert err.message and err.message in str(err)


def test_a_bad_yaml_file_names_file_line_and_column(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: x\nsources:\n  - {name: a, unit: N\n")
    with pytest.raises(deb.InputError) as e:
        deb.load(bad)
    assert e.value.file == str(bad) and e.value.line is not None and e.value.column is not None
    assert str(e.value).startswith(f"{bad}:{e.value.line}:")
    with pytest.raises(deb.InputError) as e:
        deb.load(tmp_path / "missing.yaml")
    assert "missing.yaml" in str(e.value)


def test_arrays_of_the_wrong_shape_dtype_or_non_finite_values_name_the_argument():
    args = dict(name="p", input_names=["F"], output_names=["x"], input_unit="N", output_unit="m")
    phi = np.array([[1.0]])
    cases = [
        (dict(f_hz=[1.0, np.nan], zeta=0.01, phi_in=np.ones((1, 2)), phi_out=np.ones((1, 2))), "f_hz"),
        (dict(f_hz=[1.0], zeta=[0.01, 0.02], phi_in=phi, phi_out=phi), "zeta"),
        (dict(f_hz=[1.0], zeta=0.01, phi_in=np.ones(1), phi_out=phi), "phi_in"),
        (dict(f_hz=[1.0], zeta=0.01, phi_in=phi, phi_out=np.ones((1, 2))), "phi_out"),
        (dict(f_hz=["a"], zeta=0.01, phi_in=phi, phi_out=phi), "f_hz"),
        (dict(f_hz=[1.0], zeta=0.01, phi_in=phi, phi_out=np.array([[1j]])), "phi_out"),
        (dict(f_hz=[1.0], zeta=0.01, phi_in=[[np.inf]], phi_out=phi), "phi_in"),
    ]
    for kwargs, argument in cases:
        with pytest.raises(deb.InputError) as e:
            deb.modal(**kwargs, **args)
        assert e.value.key_path == argument, kwargs
        assert str(e.value).startswith(argument + ": ")
    with pytest.raises(deb.InputError) as e:
        deb.state_space(np.eye(2), np.ones((3, 1)), np.ones((1, 2)), name="s", input_unit="N", output_unit="m")
    assert e.value.key_path == "B"
    budget = deb.load(single_mode_budget())
    for f, argument in (([1.0, np.nan], "f"), (np.ones((2, 2)), "f"), (["x"], "f")):
        with pytest.raises(deb.InputError) as e:
            deb.frequency_response(budget, "mode", f)
        assert e.value.key_path == argument
    with pytest.raises(deb.InputError) as e:
        deb.frequency_response(budget, "mdoe", [1.0])
    assert e.value.key_path == "path" and "mode" in e.value.message
    with pytest.raises(deb.InputError) as e:
        deb.evaluate(budget, threads=0)
    assert e.value.key_path == "threads"
    with pytest.raises(deb.InputError) as e:
        deb.evaluate(budget).output("nothing")
    assert e.value.key_path == "name"


def test_garbage_never_crashes_the_interpreter():
    # In a child interpreter: a crash (a signal) would fail here, not take pytest down.
    script = r"""
import deb
texts = ["", "{", "name: x", "- 1\n- 2\n", "name: x\nsources: 3\npaths: []\ncontributors: []\noutputs: []\n",
         "a: [\n", "\x00\x01\n", "name: [1, {2: 3}]\nsources: {a: b}\n"]
caught = 0
for t in texts:
    try:
        deb.load(t if "\n" in t or t.startswith("{") else t + "\n")
    except deb.InputError:
        caught += 1
for bad in ({"name": "x"}, {"name": "x", "sources": [None]}, {1: 2}):
    try:
        deb.load(bad)
    except deb.InputError:
        caught += 1
print(caught)
"""
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert int(out.stdout) == 11
