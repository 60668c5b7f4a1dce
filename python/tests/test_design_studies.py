"""deb.uncertainty and deb.optimise against the CLI's uncertainty and optimise,
and against closed forms."""

import json
import subprocess

import numpy as np
import pytest

import deb
from conftest import BUDGETS, deb_binary

TOLERANCES = BUDGETS / "nizamoglu2015_tolerances.yaml"

# Two flat sources through kv and 1/kv: variance (a kv^2 + b / kv^2) x 99 um^2,
# least at kv* = (b/a)^(1/4) = 2; the source level a uncertain (uniform).
KV_BUDGET = """name: opt
parameters:
  kv: {value: 5, min: 0.5, max: 10}
  a: {value: 1, distribution: {uniform: {min: 0.5, max: 1.5}}}
grid: {type: log, min_hz: 1, max_hz: 100, points: 50}
sources:
  - {name: sa, unit: N, spectrum: {type: flat, level: a * 1.0e-6}}
  - {name: sb, unit: N, spectrum: {type: flat, level: 16.0e-6}}
paths:
  - {name: pa, type: gain, gain: [[kv]], input_unit: N, output_unit: um}
  - {name: pb, type: gain, gain: [[1/kv]], input_unit: N, output_unit: um}
contributors:
  - {name: ca, source: sa, path: pa}
  - {name: cb, source: sb, path: pb}
outputs:
  - {name: z, signal: y, unit: um, rms_max: 0.05}
"""


def test_uncertainty_equals_deb_uncertainty(tmp_path):
    u = deb.uncertainty(TOLERANCES, samples=60, method="lhs", seed=4, threads=2)
    subprocess.run([deb_binary(), "uncertainty", str(TOLERANCES), "-n", "60", "--method", "lhs", "--seed", "4",
                    "--no-plots", "-q", "--out", str(tmp_path / "u")], check=True)
    cli = json.loads((tmp_path / "u" / "summary.json").read_text())
    python = {k: v for k, v in u.items() if not k.startswith("sample_")}
    assert python == cli
    assert u["sample_parameters"].shape == (60, 4)
    assert u["sample_metrics"].shape == (60, len(u["metrics"]))
    assert u["sample_metric_names"][0] == "z_velocity"
    # The table's column of the total is the metric's samples: its mean is the summary's.
    assert np.mean(u["sample_metrics"][:, 0]) == pytest.approx(u["metrics"][0]["mean"], rel=1e-12)


def test_uncertainty_p_meet_of_a_uniform_level_against_its_closed_form(tmp_path):
    # At kv = 5 the RMS is sqrt((25 a + 0.64) 99e-6): RMS <= 0.05 where a <= (0.05^2 / 99e-6 - 0.64) / 25.
    f = tmp_path / "b.yaml"
    f.write_text(KV_BUDGET)
    u = deb.uncertainty(f, samples=4000, method="mc", seed=2)
    z = u["metrics"][0]
    a_max = (0.05 ** 2 / 99e-6 - 0.64) / 25
    closed = (a_max - 0.5) / 1.0
    low, high = z["p_meet_95"]
    assert 0.3 < closed < 0.7
    assert low <= closed <= high


def test_optimise_finds_kv_and_equals_deb_optimise(tmp_path):
    f = tmp_path / "b.yaml"
    f.write_text(KV_BUDGET.replace(", rms_max: 0.05", ""))
    o = deb.optimise(f, ["kv"], objective="z", method="bobyqa")
    assert o["optimum"]["values"]["kv"] == pytest.approx(2.0, rel=1e-6)
    subprocess.run([deb_binary(), "optimise", str(f), "--vary", "kv", "--objective", "z", "--method", "bobyqa",
                    "--no-plots", "-q", "--out", str(tmp_path / "o")], check=True)
    assert {k: v for k, v in o.items() if k != "history"} == json.loads((tmp_path / "o" / "summary.json").read_text())
    assert o["history"] == (tmp_path / "o" / "history.csv").read_text()


def test_design_studies_raise_input_errors(tmp_path):
    f = tmp_path / "b.yaml"
    f.write_text(KV_BUDGET)
    with pytest.raises(deb.InputError) as e:
        deb.optimise(f, "kw")
    assert "--vary kw: no parameter of that name" in str(e.value)
    with pytest.raises(deb.InputError):
        deb.uncertainty(f, samples=0)
    with pytest.raises(deb.InputError) as e:
        deb.optimise(f, "kv", starts=1001)
    assert "starts must be 1 to 1000" in str(e.value)
    g = tmp_path / "c.yaml"
    g.write_text(KV_BUDGET.replace("{value: 1, distribution: {uniform: {min: 0.5, max: 1.5}}}",
                                   "{value: 1, distribution: {uniform: {min: 1.5, max: 0.5}}}"))
    with pytest.raises(deb.InputError) as e:
        deb.uncertainty(g, samples=10)
    assert e.value.key_path == "parameters.a.distribution.uniform"
    assert e.value.line == 4


def test_sensitivity_equals_deb_sensitivity_and_the_closed_form(tmp_path):
    # var = (a kv^2 + b / kv^2) x 99 um^2: d var / d ln kv = 2 (a kv^2 - b / kv^2) x 99, exactly through the
    # gains (the paths' D); the level a is a source's, by central differences: d var / d ln a = var_a.
    f = tmp_path / "b.yaml"
    f.write_text(KV_BUDGET)
    s = deb.sensitivity(f, ["kv", "a"])
    assert s["methods"]["kv"]["exact"] and s["methods"]["kv"]["note"] == "exact, through the realisation of 'pa', 'pb'"
    assert not s["methods"]["a"]["exact"] and "'ca'" in s["methods"]["a"]["note"]
    rows = {(r["parameter"], r["contributor"]): r for r in s["sensitivities"]}
    kv, a, b = 5.0, 1e-6, 16e-6
    assert rows[("kv", "total")]["method"] == "exact"
    assert rows[("kv", "total")]["d_variance_d_log_p"] == pytest.approx(2 * (a * kv**2 - b / kv**2) * 99, rel=1e-9)
    assert rows[("kv", "ca")]["elasticity"] == pytest.approx(2.0, rel=1e-9)
    assert rows[("kv", "cb")]["elasticity"] == pytest.approx(-2.0, rel=1e-9)
    assert rows[("a", "ca")]["elasticity"] == pytest.approx(1.0, rel=1e-6)  # the ln-step difference: 1 - h^2/3
    assert rows[("a", "cb")]["d_variance_d_log_p"] == 0.0
    # The CLI's sensitivity.csv, row for row.
    subprocess.run([deb_binary(), "sensitivity", str(f), "-p", "kv", "-p", "a", "-q", "--no-plots",
                    "--out", str(tmp_path / "s")], check=True)
    lines = (tmp_path / "s" / "sensitivity.csv").read_text().splitlines()
    assert lines[0] == "parameter,output,unit,contributor,variance,d_variance_d_log_p,elasticity,method"
    assert len(lines) - 1 == len(s["sensitivities"])
    for line, r in zip(lines[1:], s["sensitivities"]):
        fields = line.split(",")
        assert fields[0] == r["parameter"] and fields[3] == r["contributor"] and fields[7] == r["method"]
        assert float(fields[5]) == pytest.approx(r["d_variance_d_log_p"], rel=1e-9, abs=1e-300)
    everything = deb.sensitivity(f, "kv", central_differences=True)
    assert not everything["methods"]["kv"]["exact"]
    with pytest.raises(deb.InputError) as e:
        deb.sensitivity(f, ["kv"], step=0.9)
    assert "step" in str(e.value)
