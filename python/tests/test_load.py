"""deb.load: a file, a text and a dict load the same budget; set= overrides."""


import numpy as np
import pytest

import deb
from conftest import BUDGETS, cli_summary

FIRST = BUDGETS / "guide" / "first_budget.yaml"

# budgets/guide/first_budget.yaml as a dict, key by key.
FIRST_DICT = {
    "name": "first_budget",
    "sources": [
        {"name": "floor", "unit": "um/s", "spectrum": {"type": "vc", "class": "VC-D"}},
        {"name": "sound", "unit": "N",
         "spectrum": {"type": "flat", "quantity": "asd", "level": 0.03, "lo_hz": 20, "hi_hz": 500}},
    ],
    "paths": [
        {"name": "transmissibility", "type": "transfer_function", "num": [1.2566, 157.91],
         "den": [1, 1.2566, 157.91], "input_unit": "um/s", "output_unit": "um/s", "outputs": ["z"]},
        {"name": "compliance", "type": "transfer_function", "num": np.array([1.0]),
         "den": np.array([500, 628.3, 78957]), "input_unit": "N", "output_unit": "m", "outputs": ["z"]},
    ],
    "contributors": [
        {"name": "floor", "source": "floor", "path": "transmissibility"},
        {"name": "sound", "source": "sound", "path": "compliance"},
    ],
    "outputs": [{"name": "table_z", "signal": "z", "unit": "nm", "rms_max": 12}],
}


def traces(result):
    """Every number of a result that loading could change, as arrays."""
    out = [result.f]
    for o in result.outputs:
        out += [o.psd, o.cps, np.array([o.variance])]
        for c in o.contributors:
            out += [c.psd, c.cps, np.array([c.variance])]
    return out


def test_file_text_and_dict_give_identical_results():
    from_file = deb.evaluate(deb.load(str(FIRST)))
    from_path = deb.evaluate(deb.load(FIRST))  # a pathlib.Path
    from_text = deb.evaluate(deb.load(FIRST.read_text()))
    from_dict = deb.evaluate(deb.load(FIRST_DICT))
    assert from_file.output("table_z").rms == pytest.approx(14.54, abs=0.005)  # the README's figure
    for other in (from_path, from_text, from_dict):
        a, b = traces(from_file), traces(other)
        assert len(a) == len(b)
        for x, y in zip(a, b):
            np.testing.assert_array_equal(x, y)
    assert deb.load(FIRST_DICT).text.startswith("name: ")
    assert deb.load(FIRST).file == str(FIRST) and deb.load(FIRST).text is None


def test_set_overrides_change_the_result_as_the_cli_does(tmp_path):
    # geophone noise: a flat ASD 0.01; at 0.03 its variance is 9 times larger, the floor's unchanged.
    isolator = BUDGETS / "single_axis_isolator.yaml"
    nominal = deb.evaluate(deb.load(isolator)).outputs[0]
    changed = deb.evaluate(deb.load(isolator, set={"sources[1].spectrum.level": 0.03})).outputs[0]
    for a, b in zip(nominal.contributors, changed.contributors):
        expected = 9.0 if a.source == "geophone_noise" else 1.0
        assert b.variance / a.variance == pytest.approx(expected, rel=1e-12, abs=0)
    # The same override as text, as a list of KEY=VALUE, and on a text budget.
    text = isolator.read_text()
    for b in (deb.load(isolator, set=["sources[1].spectrum.level=0.03"]),
              deb.load(text, set={"sources[1].spectrum.level": "0.03"}, base_dir=str(BUDGETS))):
        assert deb.evaluate(b).outputs[0].variance == changed.variance
    # A parameter by its name, against deb run --set.
    thesis = BUDGETS / "nizamoglu2015_h210.yaml"
    r = deb.evaluate(thesis, set={"Kv": 100})
    cli = cli_summary(thesis, tmp_path / "kv100", "--set", "Kv=100")
    assert deb.load(thesis, set={"Kv": 100}).parameters["Kv"][0] == 100.0
    for o, c in zip(r.outputs, cli["outputs"]):
        assert o.rms == pytest.approx(c["rms"], rel=1e-12, abs=0)
    assert r.outputs[0].rms != deb.evaluate(thesis).outputs[0].rms


def test_a_bad_override_is_an_input_error():
    with pytest.raises(deb.InputError) as e:
        deb.load(BUDGETS / "single_axis_isolator.yaml", set={"sources[1].spectrum.levle": 2})
    assert "did you mean 'level'" in str(e.value)
    with pytest.raises(deb.InputError) as e:
        deb.load(BUDGETS / "single_axis_isolator.yaml", set={"sources[1].spectrum.level": -1})
    assert e.value.line == 39 and e.value.key_path == "sources[1].spectrum.level"
    with pytest.raises(deb.InputError) as e:
        deb.load(FIRST, set=["no equals sign"])
    assert e.value.key_path == "set"
