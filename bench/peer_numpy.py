#!/usr/bin/env python3
"""The script an engineer would write with numpy/scipy instead of deb, on the
same model and the same frequencies: the peer of bench/versus_numpy.

    peer_numpy.py CASE_DIR GRID_CSV [POINTS [RULE]]

CASE_DIR is a case written by `bench_modal --keep` (modes.csv, phi_in.csv,
phi_out.csv, b.yaml; with `--loop`, b.yaml's PID closed around the modal
plant) or by `bench_dense --fe ... --keep` (plant.mat). GRID_CSV is any
CSV whose first column, after comment lines (#) and one header line, holds
deb's grid (an output CSV of `deb run --export csv`). POINTS R (default 1)
divides every interval of that grid into R equal ones; POINTS log:N takes
instead N points spaced evenly in log f over the same band, as a script on
its own grid would. RULE (trapezoid, the default, or simpson) is scipy's
rule for the variance on them. Flat uncorrelated forces of 1 N^2/Hz (one-sided)
on every input, as the cases' budgets say. It prints one line of JSON: the
seconds (wall and CPU) of its own work, and for every output the grid
variance (RULE on the PSD) and the exact variance (modal closed form, or
scipy's solve_continuous_lyapunov, and for those also the closed form by A's
eigenvectors, a second method, whose seconds it prints apart), in nm^2.
For a modal case it also prints the exact variance over the grid's band
(first to last frequency), by a closed form, also apart: the reference for
the band integral the grid variance approximates; and, as its check, the
largest |variance / exact - 1| of the same form over 1e-9 to 1e12 Hz.

Needs Debian's python3-scipy (numpy, scipy); deb itself never does.
"""
import functools
import json
import re
import sys
import time

import numpy as np
import scipy.integrate
import scipy.io
import scipy.linalg
import scipy.signal

S0 = 1.0  # N^2/Hz, one-sided
NM2 = 1e18  # m^2 -> nm^2


def table(path):
    rows = [line.strip().split(",") for line in open(path).read().splitlines()[1:] if line.strip()]
    return np.array([[float(x) for x in r[1:]] for r in rows])


def modal_case(d):
    modes = np.loadtxt(d + "/modes.csv", delimiter=",", skiprows=1, ndmin=2)
    return modes[:, 1] * 2 * np.pi, modes[:, 2], table(d + "/phi_in.csv"), table(d + "/phi_out.csv")


def modal_h(w, z, pin, pout, omega):
    """H(j omega) for a block of frequencies: (frequencies, outputs, inputs)."""
    g = 1.0 / (w[None, :] ** 2 - omega[:, None] ** 2 + 2j * (z * w)[None, :] * omega[:, None])
    # Phi_out diag(g) Phi_in^T as two real matrix products per block.
    re = (pout[None, :, :] * g.real[:, None, :]) @ pin.T
    im = (pout[None, :, :] * g.imag[:, None, :]) @ pin.T
    return re + 1j * im


def modal_realisation(w, z, pin, pout):
    n = len(w)
    a = np.zeros((2 * n, 2 * n))
    a[0::2, 1::2] = np.eye(n)
    a[1::2, 0::2] = -np.diag(w ** 2)
    a[1::2, 1::2] = -np.diag(2 * z * w)
    b = np.zeros((2 * n, pin.shape[0]))
    b[1::2, :] = pin.T
    c = np.zeros((pout.shape[0], 2 * n))
    c[:, 0::2] = pout
    return a, b, c


def mode_poles(w, z):
    """Each mode's two poles and the residues there of 1/((s - l)(s - conj l)),
    both n x 2."""
    lam = -z * w + 1j * w * np.sqrt(1 - z ** 2)
    r = 1 / (lam - lam.conj())
    return np.stack([lam, lam.conj()], axis=1), np.stack([r, -r], axis=1)


CHECK_SECONDS = [0.0, 0.0]  # wall, CPU of the checks (second method, band form): not the peer's work


def timed_as_check(function):
    """`function`, its seconds counted in CHECK_SECONDS, not the peer's."""
    @functools.wraps(function)
    def timed(*args):
        wall, cpu = time.perf_counter(), time.process_time()
        try:
            return function(*args)
        finally:
            CHECK_SECONDS[0] += time.perf_counter() - wall
            CHECK_SECONDS[1] += time.process_time() - cpu
    return timed


def modal_exact(w, z, pin, pout):
    """Closed form: E[q_k q_l] from the poles of each mode, O(n^2) per output."""
    poles, res = mode_poles(w, z)
    m = np.zeros((len(w), len(w)))
    for a in range(2):
        for b in range(2):
            m += np.real(res[:, a, None] * res[None, :, b].conj() * (-1.0 / (poles[:, a, None] + poles[None, :, b].conj())))
    m *= (pin.T @ pin) * S0 / 2
    return np.einsum("ok,kl,ol->o", pout, m, pout) * NM2


@timed_as_check
def modal_band_exact(w, z, pin, pout, f1, f2):
    """The exact variance over [f1, f2] Hz, in closed form: each mode's g is
    r/(j omega - l) - r/(j omega - conj l), and the integral over omega of
    1/((j omega - p)(-j omega - conj q)) is
    -j (dL_p - conj dL_q) / (-p - conj q), dL_p = log(j omega - p) between
    the band's ends (principal logarithms: j omega - p stays in the right
    half plane). Over the whole axis it is modal_exact."""
    poles, rho = mode_poles(w, z)
    dl = np.log(2j * np.pi * f2 - poles) - np.log(2j * np.pi * f1 - poles)
    m = np.zeros((len(w), len(w)))
    for a in range(2):
        for b in range(2):
            m += np.real(rho[:, a, None] * rho[None, :, b].conj() / (-poles[:, a, None] - poles[None, :, b].conj())
                         * -1j * (dl[:, a, None] - dl[None, :, b].conj()))
    m *= (pin.T @ pin) * S0 / (2 * np.pi)  # one-sided PSD in Hz: d omega / (2 pi)
    return np.einsum("ok,kl,ol->o", pout, m, pout) * NM2


@timed_as_check
def eigen_exact(a, b, c):
    """The exact variances by A's eigenvectors, a second method beside the
    Lyapunov solve: X = V (B~ B~^H W / -(l_i + conj l_j)) V^H, B~ = V^-1 B."""
    lam, v = np.linalg.eig(a)
    bt, ct = np.linalg.solve(v, b), c @ v
    x = (bt @ bt.conj().T * S0 / 2) / (-(lam[:, None] + lam[None, :].conj()))
    return np.real(np.einsum("ik,kl,il->i", ct, x, ct.conj(), optimize=True)) * NM2


def refined(f, parts):
    """f with every interval divided into `parts` equal ones."""
    t = np.arange(parts) / parts
    inner = f[:-1, None] + (f[1:] - f[:-1])[:, None] * t[None, :]
    return np.concatenate([inner.ravel(), f[-1:]])


def psd_and_variance(h_of_block, f, outputs, rule):
    psd = np.zeros((len(f), outputs))
    for s in range(0, len(f), 64):
        h = h_of_block(2 * np.pi * f[s:s + 64])
        psd[s:s + 64] = S0 * np.sum(np.abs(h) ** 2, axis=2) * NM2
    if rule == "simpson":
        return scipy.integrate.simpson(psd, x=f, axis=0)
    return scipy.integrate.trapezoid(psd, f, axis=0)


def pid_controller(d):
    text = open(d + "/b.yaml").read()
    num, den = re.search(r"num: \[([^\]]*)\], den: \[([^\]]*)\]", text).groups()
    num = [float(x) for x in num.split(",")]
    den = [float(x) for x in den.split(",")]
    return num, den


def main():
    d, grid = sys.argv[1], sys.argv[2]
    points = sys.argv[3] if len(sys.argv) > 3 else "1"
    rule = sys.argv[4] if len(sys.argv) > 4 else "trapezoid"
    log_points = int(points[4:]) if points.startswith("log:") else 0
    parts = 1 if log_points else int(points)
    if parts < 1 or (points.startswith("log:") and log_points < 2) or rule not in ("trapezoid", "simpson"):
        sys.exit("peer_numpy.py: POINTS must be R >= 1 or log:N with N >= 2, RULE trapezoid or simpson")
    lines = [line for line in open(grid).read().splitlines() if line.strip() and not line.startswith("#")]
    f = refined(np.array([float(line.split(",")[0]) for line in lines[1:]]), parts)
    if log_points:
        f = np.logspace(np.log10(f[0]), np.log10(f[-1]), log_points)
    wall, cpu = time.perf_counter(), time.process_time()
    band_exact = None
    band_form_check = None
    text = open(d + "/b.yaml").read()
    if "plant.mat" in text:  # dense: eigendecomposition for H, Lyapunov for the exact variance
        m = scipy.io.loadmat(d + "/plant.mat")
        a, b, c = m["A"], m["B"], m["C"]
        lam, v = np.linalg.eig(a)
        left, right = c @ v, np.linalg.solve(v, b)
        h = lambda om: (left[None, :, :] * (1 / (1j * om[:, None] - lam[None, :]))[:, None, :]) @ right
        grid_var = psd_and_variance(h, f, c.shape[0], rule)
        x = scipy.linalg.solve_continuous_lyapunov(a, -b @ b.T * S0 / 2)
        exact = np.diag(c @ x @ c.T) * NM2
        by_eigenvectors = eigen_exact(a, b, c)
    else:
        w, z, pin, pout = modal_case(d)
        if "type: feedback" in text:  # the PID on y1, y2 -> F1, F2, closed per frequency and in state space
            num, den = pid_controller(d)
            k = lambda om: np.polyval(num, 1j * om) / np.polyval(den, 1j * om)

            def h(om):
                # (I + G K)^-1 G, K = diag(k, k) from y1, y2 to F1, F2: G K has
                # the columns G[:, 0] k and G[:, 1] k.
                g = modal_h(w, z, pin, pout, om)
                loop = np.zeros((g.shape[0], g.shape[1], g.shape[1]), dtype=complex)
                loop[:, :, 0:2] = g[:, :, 0:2] * k(om)[:, None, None]
                return np.linalg.solve(np.eye(g.shape[1])[None] + loop, g)

            grid_var = psd_and_variance(h, f, pout.shape[0], rule)
            ap, bp, cp = modal_realisation(w, z, pin, pout)
            ak, bk, ck, dk = scipy.signal.tf2ss(num, den)
            nk = ak.shape[0]
            aK = scipy.linalg.block_diag(ak, ak)
            bK = np.zeros((2 * nk, cp.shape[0]))
            bK[:nk, 0:1], bK[nk:, 1:2] = bk, bk
            cK = np.zeros((bp.shape[1], 2 * nk))
            cK[0:1, :nk], cK[1:2, nk:] = ck, ck
            dK = np.zeros((bp.shape[1], cp.shape[0]))
            dK[0, 0] = dK[1, 1] = dk[0, 0]
            acl = np.block([[ap - bp @ dK @ cp, -bp @ cK], [bK @ cp, aK]])
            bcl = np.vstack([bp, np.zeros((2 * nk, bp.shape[1]))])
            ccl = np.hstack([cp, np.zeros((cp.shape[0], 2 * nk))])
            x = scipy.linalg.solve_continuous_lyapunov(acl, -bcl @ bcl.T * S0 / 2)
            exact = np.diag(ccl @ x @ ccl.T) * NM2
            by_eigenvectors = eigen_exact(acl, bcl, ccl)
        else:
            grid_var = psd_and_variance(lambda om: modal_h(w, z, pin, pout, om), f, pout.shape[0], rule)
            exact = modal_exact(w, z, pin, pout)
            by_eigenvectors = exact  # the modal closed form is the eigenvector form
            band_exact = modal_band_exact(w, z, pin, pout, f[0], f[-1])
            # The band form over (nearly) the whole axis is the closed form.
            wide = modal_band_exact(w, z, pin, pout, 1e-9, 1e12)
            band_form_check = float(np.max(np.abs(wide / exact - 1)))
    print(json.dumps({"wall_s": time.perf_counter() - wall, "cpu_s": time.process_time() - cpu, "points": len(f),
                      "check_wall_s": CHECK_SECONDS[0], "check_cpu_s": CHECK_SECONDS[1],
                      "grid_variance_nm2": list(grid_var), "exact_variance_nm2": list(exact),
                      "eigenvector_variance_nm2": list(by_eigenvectors),
                      "band_exact_variance_nm2": None if band_exact is None else list(band_exact),
                      "band_form_vs_exact": band_form_check}))


if __name__ == "__main__":
    main()
