"""deb: dynamic error budgeting for precision machines, from Python.

    import deb
    b = deb.load("budgets/single_axis_isolator.yaml", set={"sources[1].spectrum.level": 0.02})
    r = deb.evaluate(b)
    out = r.output("z_velocity")
    out.rms, out.psd, out.cps, r.f          # floats; numpy arrays over r.f (Hz)

A thin layer over deb's C++ library (deb._deb); docs/python.md documents
every function.
"""

from . import _deb
from ._builders import (budget, flat_source, frf_path, measured_source, modal, state_space, transfer_function,
                        write_frf, write_spectrum, zpk)
from ._deb import Band, Budget, Comparison, Contributor, Output, Requirement, Result, SweepResult
from ._errors import InputError, WriteError
from ._load import load
from ._studies import (compare, evaluate, frequency_response, optimise, sensitivity, sweep, to_dict, uncertainty,
                       write_report)

__version__ = _deb.__version__

Result.to_dict = to_dict
Result.to_dict.__doc__ = "summary.json of this result as a dict (the text deb run writes, parsed)"
# What summary.json holds beyond the traces, read from it rather than bound
# twice: the feedback loops with their margins, the output covariance, and
# per failing output what would fix it.
Result.loops = property(lambda self: to_dict(self).get("loops", []),
                        doc="The feedback loops with their margins (summary.json's loops), a dict each")
Result.covariance = property(lambda self: to_dict(self).get("covariance"),
                             doc="The output covariance the budget asks for (summary.json's covariance), or None")
Result.guidance = property(lambda self: {o["name"]: o.get("guidance") for o in to_dict(self)["outputs"]},
                           doc="{output: what would fix it (summary.json's guidance), or None when it passes}")

__all__ = [
    "Band", "Budget", "Comparison", "Contributor", "InputError", "Output", "Requirement", "Result", "SweepResult",
    "WriteError", "budget", "compare", "evaluate", "flat_source", "frequency_response", "frf_path", "load",
    "measured_source", "modal", "optimise", "sensitivity", "state_space", "sweep", "to_dict", "transfer_function",
    "uncertainty", "write_frf", "write_report", "write_spectrum", "zpk",
]
