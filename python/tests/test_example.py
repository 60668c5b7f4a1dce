"""examples/python/modal_monte_carlo.py runs, with a few samples, and writes where it is told."""

import csv
import math
import subprocess
import sys

import deb
from conftest import SOURCE_DIR

EXAMPLE = SOURCE_DIR / "examples" / "python" / "modal_monte_carlo.py"


def test_the_monte_carlo_example_runs(tmp_path):
    out = subprocess.run([sys.executable, str(EXAMPLE), str(tmp_path / "out"), "--samples", "4"],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert "Monte Carlo, 4 samples" in out.stdout
    assert ("plot: " in out.stdout) == (tmp_path / "out" / "cps.png").is_file()
    assert "plot: " in out.stdout or "matplotlib is not installed" in out.stdout
    with open(tmp_path / "out" / "monte_carlo.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 4
    # Each row is the budget evaluated with that row's damping.
    sys.path.insert(0, str(EXAMPLE.parent))
    try:
        import modal_monte_carlo
    finally:
        sys.path.pop(0)
    zeta = [float(rows[0][k]) for k in ("zeta_45Hz", "zeta_120Hz", "zeta_310Hz")]
    rms = deb.evaluate(modal_monte_carlo.frame_budget(zeta)).output("head_z").rms
    assert math.isclose(rms, float(rows[0]["head_z_rms_nm"]), rel_tol=1e-12)


def test_without_matplotlib_the_example_skips_the_plot(tmp_path):
    # matplotlib made unimportable (a None entry in sys.modules), whether or not it is installed.
    run = ("import runpy, sys; sys.modules['matplotlib'] = None; "
           f"sys.argv = ['x', {str(tmp_path / 'out')!r}, '--samples', '2']; "
           f"runpy.run_path({str(EXAMPLE)!r}, run_name='__main__')")
    out = subprocess.run([sys.executable, "-c", run], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert "matplotlib is not installed: no plot" in out.stdout and "Monte Carlo, 2 samples" in out.stdout
    assert not (tmp_path / "out" / "cps.png").exists()
