"""Measured spectra and frequency responses from numpy arrays (write_spectrum, write_frf)."""

import math

import numpy as np
import pytest

import deb
from test_modal import MASS, STIFFNESS, h_closed_form, single_mode_budget


def test_a_measured_source_from_arrays_integrates_exactly(tmp_path):
    # A constant PSD S0 from 1 to 1000 Hz through a unit gain: variance S0 * 999 (the
    # trapezoid and the log-log interpolation are both exact on a constant).
    s0 = 2.5e-3
    f = np.logspace(0, 3, 31)
    psd = np.column_stack([np.full(f.size, s0), np.full(f.size, 4 * s0)])
    file = deb.write_spectrum(tmp_path / "floor.csv", f, psd, unit="um/s", channels=["x", "y"])
    b = deb.budget("measured", sources=[deb.measured_source("floor", file)],
                   paths=[{"name": "gain", "type": "gain", "gain": [[1.0, 0.0], [0.0, 1.0]], "inputs": ["x", "y"],
                           "outputs": ["x", "y"], "input_unit": "um/s", "output_unit": "um/s"}],
                   contributors=[("floor", "floor", "gain")],
                   outputs=[("x", "x", "um/s"), ("y", "y", "um/s")])
    r = deb.evaluate(b)
    assert r.f[0] == 1.0 and r.f[-1] == 1000.0  # the data's range: no extrapolation
    assert r.output("x").variance == pytest.approx(s0 * 999, rel=1e-12, abs=0)
    assert r.output("y").variance == pytest.approx(4 * s0 * 999, rel=1e-12, abs=0)
    with pytest.raises(deb.InputError) as e:
        deb.write_spectrum(tmp_path / "bad.csv", f, psd[:-1], unit="um/s")
    assert e.value.key_path == "psd"
    # A file the reader refuses (frequencies not increasing) is located in that file.
    bad = deb.write_spectrum(tmp_path / "bad.csv", f[::-1], psd, unit="um/s")
    b["sources"] = [deb.measured_source("floor", bad)]
    with pytest.raises(deb.InputError) as e:
        deb.load(b)
    assert e.value.file is not None and "bad.csv" in str(e.value) and e.value.line is not None


def test_measured_data_from_arrays_without_a_file():
    # The same constant PSD as above, given as arrays: the budget needs no file of the caller's.
    s0 = 2.5e-3
    f = np.logspace(0, 3, 31)
    b = deb.budget("measured", sources=[deb.measured_source("floor", f_hz=f, psd=np.full(f.size, s0), unit="um/s")],
                   paths=[{"name": "gain", "type": "gain", "gain": [[1.0]], "input_unit": "um/s",
                           "output_unit": "um/s"}],
                   contributors=[("floor", "floor", "gain")], outputs=[("x", "y", "um/s")])
    assert deb.evaluate(b).output("x").variance == pytest.approx(s0 * 999, rel=1e-12, abs=0)
    # An FRF as arrays: H of one mass, read back at its points.
    w = 2 * np.pi * f
    h = (1.0 / (1e4 - 2.0 * w ** 2 + 1j * 5.0 * w)).reshape(-1, 1, 1)
    p = deb.frf_path("m", f_hz=f, h=h, input_unit="N", output_unit="m")
    b2 = deb.budget("frf", sources=[deb.flat_source("force", 1e-4, unit="N", channels=["u1"])], paths=[p],
                    contributors=[("force", "force", "m")], outputs=[("x", "y1", "m")])
    got = deb.frequency_response(b2, "m", f[5:8])
    assert np.allclose(got[:, 0, 0], h[5:8, 0, 0], rtol=1e-15, atol=0)
    with pytest.raises(deb.InputError) as e:
        deb.measured_source("floor", f_hz=f, psd=np.full(f.size, s0))
    assert e.value.key_path == "unit"


def test_an_frf_path_from_arrays_equals_the_model_it_was_sampled_from(tmp_path):
    # The single mode's H sampled at 3000 frequencies, written, read back as a measured path:
    # at the data's frequencies H is the data, to every digit written.
    f = np.logspace(0, 3, 3000)
    h = h_closed_form(f)[:, None, None]
    file = deb.write_frf(tmp_path / "mode.csv", f, h, outputs=["x"], inputs=["F"])
    b = single_mode_budget()
    b["paths"] = [deb.frf_path("mode", file, input_unit="N", output_unit="m")]
    measured = deb.load(b)
    np.testing.assert_allclose(deb.frequency_response(measured, "mode", f), h, rtol=1e-15, atol=0)
    # Between the points the interpolation (polar, linear in log f) is close to the model:
    # measured 1.7e-3 at the resonance (points 0.23 % apart, its half-width 2 %), 1.9e-5
    # beyond 20 % of it; the variance over the data's range within 5.2e-4 of the model's
    # on the same grid.
    mid = np.sqrt(f[:-1] * f[1:])
    error = np.abs(deb.frequency_response(measured, "mode", mid)[:, 0, 0] / h_closed_form(mid) - 1)
    f_n = math.sqrt(STIFFNESS / MASS) / (2 * math.pi)
    assert error.max() < 2e-3 and error[np.abs(mid / f_n - 1) > 0.2].max() < 1e-4
    r = deb.evaluate(measured)
    modal = deb.evaluate(single_mode_budget(grid={"type": "explicit", "f_hz": r.f}))
    assert r.output("x").variance == pytest.approx(modal.output("x").variance, rel=1e-3, abs=0)
    with pytest.raises(deb.InputError) as e:
        deb.write_frf(tmp_path / "bad.csv", f, h[:, :, 0], outputs=["x"], inputs=["F"])
    assert e.value.key_path == "h"
    with pytest.raises(deb.InputError) as e:
        deb.write_frf(tmp_path / "bad.csv", f, h, outputs=["x y"], inputs=["F"])
    assert e.value.key_path == "outputs"
