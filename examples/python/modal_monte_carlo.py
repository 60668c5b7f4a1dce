#!/usr/bin/env python3
"""A modal path from numpy arrays, its CPS, and a Monte Carlo over its damping.

A frame with three modes (45, 120 and 310 Hz; mass-normalised shapes at the
two forces and the head) is driven by a white stage force and a band-limited
fan force; the output is the head's displacement in nm. The script
evaluates it once, plots the cumulative power spectrum of each contributor
(with matplotlib, if it is installed), then draws the modal damping ratios
at random (log-normal around 2 %, 30 % spread, seeded) and evaluates the
budget once per sample, which is what deb.evaluate in a Python loop is for.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/modal_monte_carlo.py OUT_DIR [--samples 50]

Writes OUT_DIR/cps.png (with matplotlib) and OUT_DIR/monte_carlo.csv
(one row per sample: the damping ratios and the head's RMS).
"""

import argparse
import csv
import math
import os
import sys

import numpy as np

import deb

F_HZ = np.array([45.0, 120.0, 310.0])
PHI_IN = np.array([[0.12, 0.25, -0.18],    # F_stage, 1/sqrt(kg) per mode
                   [0.05, -0.20, 0.30]])   # F_fan
PHI_OUT = np.array([[0.10, -0.15, 0.22]])  # z_head


def frame_budget(zeta):
    """The budget as a dict, with one damping ratio per mode."""
    return deb.budget(
        "modal_monte_carlo",
        sources=[deb.flat_source("stage_force", 1e-4, unit="N"),
                 deb.flat_source("fan_force", 0.02, unit="N", quantity="asd", lo_hz=50, hi_hz=400)],
        paths=[deb.modal(F_HZ, zeta, PHI_IN[:1], PHI_OUT, name="frame_stage", input_names=["F_stage"],
                         output_names=["z_head"], input_unit="N", output_unit="m"),
               deb.modal(F_HZ, zeta, PHI_IN[1:], PHI_OUT, name="frame_fan", input_names=["F_fan"],
                         output_names=["z_head"], input_unit="N", output_unit="m")],
        contributors=[("stage", "stage_force", "frame_stage"), ("fan", "fan_force", "frame_fan")],
        outputs=[("head_z", "z_head", "nm")],
    )


def plot_cps(result, out_dir):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot (Debian: apt install python3-matplotlib)")
        return None
    head = result.output("head_z")
    fig, ax = plt.subplots(figsize=(7, 4))
    for c in head.contributors:
        ax.semilogx(result.f, np.sqrt(c.cps), label=f"{c.name} ({c.rms:.3g} nm)")
    ax.semilogx(result.f, np.sqrt(head.cps), "k", label=f"total ({head.rms:.3g} nm)")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("cumulative RMS [nm]")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    path = os.path.join(out_dir, "cps.png")
    fig.savefig(path, dpi=120, bbox_inches="tight")
    print(f"plot: {path}")
    return path


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", help="where cps.png and monte_carlo.csv go (created)")
    parser.add_argument("--samples", type=int, default=50)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    os.makedirs(args.out_dir, exist_ok=True)

    nominal = deb.evaluate(frame_budget(0.02))
    head = nominal.output("head_z")
    print(f"nominal: head_z rms {head.rms:.6g} nm over {len(nominal.f)} frequencies")
    for c in head.contributors:
        exact = "-" if c.exact_variance is None else f"{math.sqrt(c.exact_variance):.6g}"
        print(f"  {c.name:6s} rms {c.rms:.6g} nm, exact {exact}")
    plot_cps(nominal, args.out_dir)

    rng = np.random.default_rng(args.seed)
    rms = []
    with open(os.path.join(args.out_dir, "monte_carlo.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["zeta_45Hz", "zeta_120Hz", "zeta_310Hz", "head_z_rms_nm"])
        for _ in range(args.samples):
            zeta = 0.02 * np.exp(0.3 * rng.standard_normal(3))
            r = deb.evaluate(frame_budget(zeta), threads=1).output("head_z").rms
            rms.append(r)
            w.writerow([*(repr(float(z)) for z in zeta), repr(r)])
    rms = np.array(rms)
    print(f"Monte Carlo, {args.samples} samples of the damping: head_z rms mean {rms.mean():.6g} nm, "
          f"std {rms.std(ddof=1) if len(rms) > 1 else 0.0:.3g} nm, "
          f"5-95 % {np.percentile(rms, 5):.6g}-{np.percentile(rms, 95):.6g} nm")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
