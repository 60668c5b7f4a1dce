#!/usr/bin/env python3
"""deb.evaluate against the C++ library's Evaluate on the same budget.

Times deb.evaluate on a loaded deb.Budget (one thread and every thread,
best of REPEATS) against two C++ figures: deb::Evaluate's own wall time
inside the same call (Result.seconds, measured by the module around the
library call: what the binding adds), and build/bin/bench_budgets on the
same file (deb::Evaluate in a C++ program, best of 5: a separate process,
so the machine's load moves it by more than the binding's cost). Then the
time to get every array of a 1000-mode result (views, no copy).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_evaluate.py [BUDGET.yaml] [--repeats 30]
"""

import argparse
import pathlib
import subprocess
import sys
import time

import numpy as np

import deb

ROOT = pathlib.Path(__file__).resolve().parents[1]


def best(fn, repeats):
    t = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        t.append(time.perf_counter() - t0)
    return min(t)


def evaluate_times(b, threads, repeats):
    """(best wall time of deb.evaluate, best Evaluate time inside it), seconds."""
    call, inside = [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        r = deb.evaluate(b, threads=threads)
        call.append(time.perf_counter() - t0)
        inside.append(r.seconds)
    return min(call), min(inside)


def cxx_times(bench, budget):
    """(eval 1t ms, eval all ms) from bench_budgets' table."""
    out = subprocess.run([bench, str(budget)], check=True, capture_output=True, text=True).stdout.splitlines()
    fields = out[1].split()
    return float(fields[3]), float(fields[4])


def modal_budget(modes, dofs):
    rng = np.random.default_rng(1)
    f_hz = np.sort(rng.uniform(5.0, 500.0, modes))
    names = [f"d{i}" for i in range(dofs)]
    return deb.budget(
        "modal_bench",
        sources=[deb.flat_source("force", 1e-2, unit="N", channels=dofs)],
        paths=[deb.modal(f_hz, 0.02, rng.standard_normal((dofs, modes)), rng.standard_normal((dofs, modes)),
                         name="frame", input_names=names, output_names=names, input_unit="N", output_unit="nm")],
        contributors=[("force", "force", "frame")],
        outputs=[("y", "d0", "nm")],
    )


def main(argv):
    parser = argparse.ArgumentParser()
    parser.add_argument("budget", nargs="?", default=str(ROOT / "budgets" / "nizamoglu2015_h210.yaml"))
    parser.add_argument("--repeats", type=int, default=30)
    parser.add_argument("--bench", default=str(ROOT / "build" / "bin" / "bench_budgets"))
    args = parser.parse_args(argv)
    b = deb.load(args.budget)
    for threads, label, column in ((1, "1 thread", 0), (None, "all threads", 1)):
        call, inside = evaluate_times(b, threads, args.repeats)
        cxx = cxx_times(args.bench, args.budget)[column] / 1e3
        print(f"{b.name}, {label}: deb.evaluate {1e3 * call:.3f} ms; deb::Evaluate inside it {1e3 * inside:.3f} ms "
              f"(ratio {call / inside:.3f}); bench_budgets {1e3 * cxx:.3f} ms (ratio {call / cxx:.3f})")
    r = deb.evaluate(modal_budget(1000, 20))
    t = best(lambda: [c.psd for o in r.outputs for c in o.contributors] + [r.f], 20)
    print(f"1000 modes x 20 DOFs, {len(r.f)} frequencies: the arrays of a result in {1e6 * t:.1f} us "
          f"(views: {not r.output('y').psd.flags.owndata})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
