"""deb.sweep, deb.compare and deb.write_report against the CLI's sweep, compare and run."""

import json
import subprocess

import pytest

import deb
from conftest import BUDGETS, cli_summary, deb_binary
from test_modal import single_mode_budget

THESIS_SWEEP = BUDGETS / "nizamoglu2015_sweep.yaml"


def test_the_sweep_section_of_a_file_equals_deb_sweep(tmp_path):
    s = deb.sweep(THESIS_SWEEP, threads=2)
    assert len(s) == 32 and s.values.shape == (32, 2) and len(s.results) == 32
    subprocess.run([deb_binary(), "sweep", str(THESIS_SWEEP), "--no-plots", "--quiet", "--out", str(tmp_path / "s")],
                   check=True, stdout=subprocess.DEVNULL)
    assert s.csv() == (tmp_path / "s" / "sweep.csv").read_text()
    # The last parameter varies fastest: variant 1 is gains 0, position -100.
    assert list(s.values[1]) == [0.0, -100.0]


def test_a_sweep_from_python_equals_set_overrides():
    b = single_mode_budget()
    s = deb.sweep(b, parameters={"sources[0].spectrum.level": [0.01, 0.04]})
    assert s.parameters == ["sources[0].spectrum.level"]
    one = deb.evaluate(deb.load(b, set={"sources[0].spectrum.level": 0.04}))
    assert s.results[1].outputs[0].variance == one.outputs[0].variance
    variances = [res.outputs[0].variance for res in s.results]
    assert variances[1] == pytest.approx(4 * variances[0], rel=1e-12, abs=0)
    with pytest.raises(deb.InputError) as e:
        deb.sweep(b, parameters={"sources[0].spectrum.levle": [1.0]})
    assert "levle" in str(e.value)


def test_compare_equals_deb_compare(tmp_path):
    a = BUDGETS / "nizamoglu2015_h0.yaml"
    b = BUDGETS / "nizamoglu2015_h210.yaml"
    c = deb.compare(a, b)
    subprocess.run([deb_binary(), "compare", str(a), str(b), "--no-plots", "--quiet", "--out", str(tmp_path / "c")],
                   check=True, stdout=subprocess.DEVNULL)
    assert json.loads(c.json()) == json.loads((tmp_path / "c" / "compare.json").read_text())
    total = [f for f in c.figures if f["contributor"] == "total" and f["band"] is None]
    ra, rb = deb.evaluate(a), deb.evaluate(b)
    for f, oa, ob in zip(total, ra.outputs, rb.outputs, strict=True):
        assert f["rms_a"] == oa.rms and f["rms_b"] == ob.rms


def test_write_report_equals_deb_run(tmp_path):
    budget = BUDGETS / "single_axis_isolator.yaml"
    cli = cli_summary(budget, tmp_path / "cli")
    manifest = deb.write_report(budget, tmp_path / "py", plots=False)
    assert "index.html" in manifest["files"] and "report.md" in manifest["files"] and manifest["plots"] == []
    for name in ("summary.json", "result.h5", "index.html", "report.md"):
        assert (tmp_path / "py" / name).is_file(), name
    ours = json.loads((tmp_path / "py" / "summary.json").read_text())
    ours.pop("seconds"), cli.pop("seconds")
    assert ours == cli
    # A result, written twice: the second replaces the first (deb wrote it).
    r = deb.evaluate(single_mode_budget())
    deb.write_report(r, tmp_path / "mode", plots=False)
    deb.write_report(r, tmp_path / "mode", plots=False, exports=["csv"])
    assert (tmp_path / "mode" / "x.csv").is_file()
    with pytest.raises(deb.InputError):
        deb.write_report(r, tmp_path / "bad", formats=["gif"])
    (tmp_path / "not_deb").mkdir()
    (tmp_path / "not_deb" / "mine.txt").write_text("keep")
    with pytest.raises(deb.WriteError):
        deb.write_report(r, tmp_path / "not_deb", plots=False)
    assert (tmp_path / "not_deb" / "mine.txt").read_text() == "keep"


def test_loops_covariance_and_guidance_are_summary_json_s():
    r = deb.evaluate(BUDGETS / "wafer_stage.yaml")
    d = r.to_dict()
    assert r.loops == d["loops"] and r.loops[0]["controller"] == "controller"
    assert r.loops[0]["phase_margin"]["deg"] > 0
    assert r.guidance["position"]["sentence"].startswith("position fails by")
    assert r.covariance is None
    thesis = deb.evaluate(BUDGETS / "nizamoglu2015_h210.yaml")
    assert thesis.covariance is not None and thesis.covariance == thesis.to_dict()["covariance"]
    assert deb.evaluate(BUDGETS / "guide" / "first_budget.yaml").loops == []
