"""Every budget in budgets/ evaluated through Python equals deb run's summary.json."""

import pytest

import deb
from conftest import BUDGETS, cli_summary

ALL_BUDGETS = sorted(BUDGETS.glob("*.yaml")) + sorted((BUDGETS / "guide").glob("*.yaml"))


def close(a, b, rel=1e-12):
    if a is None or b is None:
        return a is b
    return abs(a - b) <= rel * max(abs(a), abs(b))


@pytest.mark.parametrize("budget", ALL_BUDGETS, ids=lambda p: p.stem)
def test_python_equals_the_cli_summary(budget, tmp_path):
    cli = cli_summary(budget, tmp_path / "report")
    r = deb.evaluate(budget)
    assert [o.name for o in r.outputs] == [o["name"] for o in cli["outputs"]]
    for o, c in zip(r.outputs, cli["outputs"]):
        assert close(o.rms, c["rms"]) and close(o.variance, c["variance"]), o.name
        for pc, cc in zip(o.contributors, c["contributors"], strict=True):
            assert pc.name == cc["name"]
            assert close(pc.rms, cc["rms"]) and close(pc.variance, cc["variance"]), (o.name, pc.name)
            assert close(pc.exact_variance, cc["exact_variance"]), (o.name, pc.name)
        for pb, cb in zip(o.bands, c["bands"], strict=True):
            assert (pb.lo_hz, pb.hi_hz) == (cb["lo_hz"], cb["hi_hz"]) and close(pb.rms, cb["rms"])
    # to_dict() is summary.json's own text (deb::SummaryJson), parsed: equal
    # but for the wall time.
    d = r.to_dict()
    assert d.pop("seconds") >= 0 and cli.pop("seconds") >= 0
    assert d == cli
