"""A modal path built from numpy arrays against the closed form of one mode.

One mode of a mass m on a spring k with damping ratio zeta, mass-normalised
(phi = 1/sqrt(m) at the force input and the displacement output):

    H(s) = phi^2 / (s^2 + 2 zeta w_n s + w_n^2) = 1 / (m s^2 + c s + k),
    w_n = sqrt(k/m), c = 2 zeta m w_n.

A white force of one-sided PSD S0 (N^2/Hz; deb's convention: variance =
integral of S over 0..infinity in Hz, docs/method.md) gives the displacement
variance

    sigma^2 = integral_0^inf S0 |H(j 2 pi f)|^2 df
            = S0/(2 pi) * (1/2) integral_-inf^inf d w / |k - m w^2 + j c w|^2
            = S0/(4 pi) * pi/(k c) = S0 / (4 k c) = S0 / (8 zeta m^2 w_n^3).
"""

import math

import numpy as np
import pytest

import deb

MASS, STIFFNESS, ZETA, S0 = 2.5, 4.0e4, 0.02, 1.0e-2  # kg, N/m, 1, N^2/Hz


def single_mode_budget(zeta=ZETA, grid=None):
    w_n = math.sqrt(STIFFNESS / MASS)
    phi = np.array([[1.0 / math.sqrt(MASS)]])
    return deb.budget(
        "single_mode",
        sources=[deb.flat_source("force", S0, unit="N")],
        paths=[deb.modal([w_n / (2 * math.pi)], zeta, phi, phi, name="mode", input_names=["F"],
                         output_names=["x"], input_unit="N", output_unit="m")],
        contributors=[("force", "force", "mode")],
        outputs=[("x", "x", "m")],
        grid=grid,
    )


def closed_form_variance():
    w_n = math.sqrt(STIFFNESS / MASS)
    return S0 / (8 * ZETA * MASS**2 * w_n**3)


def h_closed_form(f_hz):
    w = 2 * np.pi * np.asarray(f_hz)
    c = 2 * ZETA * math.sqrt(STIFFNESS * MASS)
    return 1.0 / (STIFFNESS - MASS * w**2 + 1j * c * w)


def test_exact_variance_equals_the_closed_form():
    r = deb.evaluate(deb.load(single_mode_budget()))
    c = r.output("x").contributor("force")
    assert c.exact_variance == pytest.approx(closed_form_variance(), rel=1e-12, abs=0)
    # The grid's integral, over 0.1-1000 Hz by default, misses the static
    # tail below 0.1 Hz, about S0/k^2 * 0.1 Hz (1.3e-4 of the variance here),
    # and the f^-4 tail above (7e-8); deb's estimate of both tails added, it
    # is within 1e-6 of the closed form (measured: 9.3e-8).
    f_min = r.f[0]
    assert closed_form_variance() - c.variance == pytest.approx(S0 * f_min / STIFFNESS**2, rel=0.01, abs=0)
    assert c.variance + c.tail_variance_estimate == pytest.approx(closed_form_variance(), rel=1e-6, abs=0)
    # On a grid six decades either side of the mode the tails vanish (measured: 1.0e-7).
    wide = deb.evaluate(single_mode_budget(grid={"type": "auto", "min_hz": 1e-6, "max_hz": 1e6}))
    assert wide.output("x").variance == pytest.approx(closed_form_variance(), rel=1e-6, abs=0)
    assert r.output("x").rms == pytest.approx(math.sqrt(c.variance), rel=1e-15, abs=0)


def test_psd_and_frequency_response_equal_the_closed_form():
    b = deb.load(single_mode_budget())
    r = deb.evaluate(b)
    h = h_closed_form(r.f)
    np.testing.assert_allclose(r.output("x").psd, S0 * np.abs(h) ** 2, rtol=1e-12, atol=0)
    f = np.array([0.5, 10.0, 20.0, math.sqrt(STIFFNESS / MASS) / (2 * math.pi), 100.0, 1e4])
    resp = deb.frequency_response(b, "mode", f)
    assert resp.shape == (len(f), 1, 1) and resp.dtype == np.complex128
    np.testing.assert_allclose(resp[:, 0, 0], h_closed_form(f), rtol=1e-12, atol=0)


def test_arrays_have_the_documented_shapes_and_dtypes():
    r = deb.evaluate(single_mode_budget())
    o = r.output("x")
    n = len(r.f)
    assert r.f.dtype == np.float64 and r.f.shape == (n,) and np.all(np.diff(r.f) > 0)
    for a in (o.psd, o.cps, o.contributors[0].psd, o.contributors[0].cps):
        assert a.dtype == np.float64 and a.shape == (n,)
        assert not a.flags.writeable  # views of the result, not copies
    assert o.cps[-1] == pytest.approx(o.variance, rel=1e-15, abs=0)
    assert len(o.bands) == 4 and o.bands[0].contributor_variance.shape == (1,)  # the grid's decades
    assert sum(b.variance for b in o.bands) == pytest.approx(o.variance, rel=1e-12, abs=0)
    # A view keeps its result alive after every Python object of it is gone.
    psd = deb.evaluate(single_mode_budget()).output("x").psd
    assert np.array_equal(psd, o.psd)


def test_a_state_space_path_from_arrays_equals_the_modal_one():
    # The same oscillator, x'' = (F - c x' - k x)/m as a state space.
    c = 2 * ZETA * math.sqrt(STIFFNESS * MASS)
    A = np.array([[0.0, 1.0], [-STIFFNESS / MASS, -c / MASS]])
    B = np.array([[0.0], [1.0 / MASS]])
    C = np.array([[1.0, 0.0]])
    b = single_mode_budget()
    b["paths"] = [deb.state_space(A, B, C, name="mode", inputs=["F"], outputs=["x"], input_unit="N",
                                  output_unit="m")]
    r = deb.evaluate(b)
    exact = r.output("x").contributor("force").exact_variance
    assert exact == pytest.approx(closed_form_variance(), rel=1e-12, abs=0)
    f = np.array([1.0, 20.0, 200.0])
    np.testing.assert_allclose(deb.frequency_response(deb.load(b), "mode", f)[:, 0, 0], h_closed_form(f), rtol=1e-12)
    # As zeros, poles and gain: no zeros, the roots of m s^2 + c s + k, gain 1/m.
    b["paths"] = [deb.zpk([], np.roots([MASS, c, STIFFNESS]), 1.0 / MASS, name="mode", outputs=["x"],
                          input_unit="N", output_unit="m")]
    assert b["paths"][0]["poles"][0]["zeta"] == pytest.approx(ZETA, rel=1e-12, abs=0)
    np.testing.assert_allclose(deb.frequency_response(deb.load(b), "mode", f)[:, 0, 0], h_closed_form(f), rtol=1e-12)
    with pytest.raises(deb.InputError) as e:
        deb.zpk([], [-1 + 2j], 1.0, name="p", input_unit="N", output_unit="m")
    assert e.value.key_path == "poles" and "conjugate" in e.value.message
    # As a transfer function 1 / (m s^2 + c s + k).
    b["paths"] = [deb.transfer_function([1.0], [MASS, c, STIFFNESS], name="mode", outputs=["x"], input_unit="N",
                                        output_unit="m")]
    np.testing.assert_allclose(deb.frequency_response(deb.load(b), "mode", f)[:, 0, 0], h_closed_form(f), rtol=1e-12)


def test_threads_do_not_change_the_numbers():
    for budget in (single_mode_budget(), "budgets/wafer_stage.yaml"):
        if isinstance(budget, str):
            from conftest import SOURCE_DIR
            budget = SOURCE_DIR / budget
        one, two = deb.evaluate(budget, threads=1), deb.evaluate(budget, threads=2)
        np.testing.assert_array_equal(one.f, two.f)
        for a, b in zip(one.outputs, two.outputs):
            assert a.variance == b.variance
            np.testing.assert_array_equal(a.psd, b.psd)
            for ca, cb in zip(a.contributors, b.contributors):
                np.testing.assert_array_equal(ca.cps, cb.cps)
                assert ca.exact_variance == cb.exact_variance


def test_python_threads_evaluate_one_budget_at_once():
    # The GIL is released while evaluating: two Python threads evaluate the same
    # deb.Budget concurrently and get the numbers of a lone evaluation.
    from concurrent.futures import ThreadPoolExecutor

    from conftest import SOURCE_DIR
    b = deb.load(SOURCE_DIR / "budgets" / "wafer_stage.yaml")
    alone = deb.evaluate(b, threads=1)
    with ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(lambda _: deb.evaluate(b, threads=1), range(4)))
    for r in results:
        for a, o in zip(alone.outputs, r.outputs, strict=True):
            np.testing.assert_array_equal(a.psd, o.psd)
