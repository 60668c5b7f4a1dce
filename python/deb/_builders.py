"""Sources, paths and budgets from numpy arrays, without a file.

Each function returns the dict of one entry of a budget file (a source, a
path) in the file's layout, and deb.budget() the whole mapping; deb.load()
writes it out as YAML and loads it, so every rule of a budget file applies
and an error names the key (paths[0].damping) and the line of that text.
Here only the arrays are checked: numbers, finite, and of the documented
shape, else deb.InputError naming the argument.
"""

import atexit
import itertools
import os
import shutil
import tempfile

import numpy as np

from ._errors import argument_error

_data_dir = None
_data_names = itertools.count(1)


def _data_file(stem):
    """A fresh file name in this process's own temporary directory (removed
    when the interpreter exits): where measured_source and frf_path put the
    arrays they are given, since a budget reads measured data from files. A
    budget reads them when it is loaded; the names are never reused."""
    global _data_dir
    if _data_dir is None:
        _data_dir = tempfile.mkdtemp(prefix="deb_python_")
        atexit.register(shutil.rmtree, _data_dir, True)
    return os.path.join(_data_dir, f"{next(_data_names)}_{stem}.csv")


def real_array(value, argument, ndim):
    """value as a float64 array of `ndim` dimensions (a scalar or a list is
    promoted for ndim 1), every element finite."""
    try:
        array = np.asarray(value)
    except (TypeError, ValueError) as e:
        raise argument_error(argument, f"not an array of numbers ({e})") from None
    if array.dtype.kind not in "fiu":
        raise argument_error(argument, f"expected real numbers, got dtype {array.dtype}")
    array = array.astype(np.float64)
    if ndim == 1 and array.ndim == 0:
        array = array.reshape(1)
    if array.ndim != ndim:
        raise argument_error(argument, f"expected a {ndim}-D array, got shape {array.shape}")
    bad = np.argwhere(~np.isfinite(array))
    if bad.size:
        where = tuple(int(i) for i in bad[0])
        raise argument_error(argument, f"element {where if ndim > 1 else where[0]} is {array[tuple(bad[0])]}; "
                                       "every value must be finite")
    return array


def _names(names, count, argument, default):
    if names is None:
        return [default] if count == 1 else [f"{default}{i + 1}" for i in range(count)]
    names = [str(n) for n in names]
    if len(names) != count:
        raise argument_error(argument, f"expected {count} names, got {len(names)}")
    return names


def _common(entry, name, description, input_unit, output_unit):
    entry["name"] = name
    if description is not None:
        entry["description"] = description
    entry["input_unit" if isinstance(input_unit, str) else "input_units"] = input_unit
    entry["output_unit" if isinstance(output_unit, str) else "output_units"] = output_unit
    return entry


def state_space(A, B, C, D=None, *, name, input_unit, output_unit, inputs=None, outputs=None, description=None):
    """A path x' = A x + B u, y = C x + D u (`type: state_space`).

    A (n, n), B (n, m), C (p, n), D (p, m) or None (zeros); inputs/outputs:
    m and p channel names (default u/y, or u1.., y1..); units: one str for
    every channel, or a list of one per channel.
    """
    a = real_array(A, "A", 2)
    b = real_array(B, "B", 2)
    c = real_array(C, "C", 2)
    n = a.shape[0]
    if a.shape != (n, n):
        raise argument_error("A", f"expected a square matrix, got shape {a.shape}")
    if b.shape[0] != n:
        raise argument_error("B", f"expected {n} rows (A is {n} x {n}), got shape {b.shape}")
    if c.shape[1] != n:
        raise argument_error("C", f"expected {n} columns (A is {n} x {n}), got shape {c.shape}")
    m, p = b.shape[1], c.shape[0]
    entry = {"type": "state_space", "A": a, "B": b, "C": c}
    if D is not None:
        d = real_array(D, "D", 2)
        if d.shape != (p, m):
            raise argument_error("D", f"expected shape ({p}, {m}) (C's rows, B's columns), got {d.shape}")
        entry["D"] = d
    entry["inputs"] = _names(inputs, m, "inputs", "u")
    entry["outputs"] = _names(outputs, p, "outputs", "y")
    return _common(entry, name, description, input_unit, output_unit)


def transfer_function(num, den, *, name, input_unit, output_unit, inputs=None, outputs=None, description=None):
    """A SISO path num(s) / den(s) (`type: transfer_function`), coefficients
    highest power of s first (numpy.polyval's order)."""
    entry = {"type": "transfer_function", "num": real_array(num, "num", 1), "den": real_array(den, "den", 1)}
    entry["inputs"] = _names(inputs, 1, "inputs", "u")
    entry["outputs"] = _names(outputs, 1, "outputs", "y")
    return _common(entry, name, description, input_unit, output_unit)


def _zpk_roots(roots, argument):
    """Roots of s (rad/s) as deb's zpk entries: a real root r is f_hz = -r/(2 pi)
    (the factor s + 2 pi f), a conjugate pair {f_hz, zeta} (the factor
    s^2 + 2 zeta w s + w^2, w = |root|, zeta = -Re(root)/w)."""
    try:
        r = np.atleast_1d(np.asarray(roots, dtype=np.complex128))
    except (TypeError, ValueError) as e:
        raise argument_error(argument, f"not an array of numbers ({e})") from None
    if r.ndim != 1:
        raise argument_error(argument, f"expected a 1-D array, got shape {r.shape}")
    if not np.all(np.isfinite(r)):
        raise argument_error(argument, "every root must be finite")
    out, upper, lower = [], [], []
    for root in r:
        if root.imag == 0.0:
            out.append(float(-root.real / (2 * np.pi)))
        else:
            (upper if root.imag > 0 else lower).append(root)
    for root in upper:
        match = [k for k, c in enumerate(lower) if abs(c - root.conjugate()) <= 1e-12 * abs(root)]
        if not match:
            raise argument_error(argument, f"the complex root {root} has no conjugate")
        lower.pop(match[0])
        w = abs(root)
        out.append({"f_hz": float(w / (2 * np.pi)), "zeta": float(-root.real / w)})
    if lower:
        raise argument_error(argument, f"the complex root {lower[0]} has no conjugate")
    return out


def zpk(zeros, poles, gain, *, name, input_unit, output_unit, inputs=None, outputs=None, description=None):
    """A SISO path gain * prod(s - zeros) / prod(s - poles) (`type: zpk`),
    the roots of s in rad/s as scipy.signal's zpk form takes them (complex
    ones in conjugate pairs, each pair written as {f_hz, zeta})."""
    entry = {"type": "zpk", "zeros": _zpk_roots(zeros, "zeros"), "poles": _zpk_roots(poles, "poles"),
             "gain": float(real_array(gain, "gain", 1)[0])}
    entry["inputs"] = _names(inputs, 1, "inputs", "u")
    entry["outputs"] = _names(outputs, 1, "outputs", "y")
    return _common(entry, name, description, input_unit, output_unit)


def modal(f_hz, zeta, phi_in, phi_out, *, name, input_names, output_names, input_unit, output_unit,
          output_quantity="displacement", description=None):
    """A path of mass-normalised modes (`type: modal`):

        H(s) = sum_k phi_out[:, k] phi_in[:, k]^T / (s^2 + 2 zeta_k w_k s + w_k^2),  w_k = 2 pi f_hz[k]

    f_hz (modes,), zeta (modes,) or one number, phi_in (inputs, modes),
    phi_out (outputs, modes): each row a DOF, named by input_names and
    output_names. output_unit is the displacement unit (output_quantity
    velocity or acceleration differentiates).
    """
    f = real_array(f_hz, "f_hz", 1)
    z = real_array(zeta, "zeta", 1)
    if z.size not in (1, f.size):
        raise argument_error("zeta", f"expected one ratio or one per mode ({f.size}), got {z.size}")
    phi_i = real_array(phi_in, "phi_in", 2)
    phi_o = real_array(phi_out, "phi_out", 2)
    for arg, phi, names in (("phi_in", phi_i, input_names), ("phi_out", phi_o, output_names)):
        if phi.shape[1] != f.size:
            raise argument_error(arg, f"expected one column per mode ({f.size}), got shape {phi.shape}")
        if len(names) != phi.shape[0]:
            raise argument_error(arg, f"{phi.shape[0]} rows but {len(names)} names")
    entry = {
        "type": "modal",
        "frequencies_hz": f,
        "damping": float(z[0]) if z.size == 1 else z,
        "input_shapes": {str(n): phi_i[i] for i, n in enumerate(input_names)},
        "output_shapes": {str(n): phi_o[i] for i, n in enumerate(output_names)},
        "output_quantity": output_quantity,
    }
    return _common(entry, name, description, input_unit, output_unit)


def flat_source(name, level, *, unit, quantity="psd", channels=None, lo_hz=None, hi_hz=None, description=None):
    """A flat spectrum (`type: flat`): a one-sided PSD level in unit^2/Hz
    (quantity="asd": an ASD in unit/sqrt(Hz)), optionally band-limited; without
    band limits it is white and its contributors get an exact variance."""
    spectrum = {"type": "flat", "quantity": quantity, "level": float(real_array(level, "level", 1)[0])}
    if lo_hz is not None:
        spectrum["lo_hz"] = float(lo_hz)
    if hi_hz is not None:
        spectrum["hi_hz"] = float(hi_hz)
    entry = {"name": name, "unit": unit, "spectrum": spectrum}
    if channels is not None:
        entry["channels"] = channels if isinstance(channels, int) else [str(c) for c in channels]
    if description is not None:
        entry["description"] = description
    return entry


def budget(name, *, sources, paths, contributors, outputs, bands=None, grid=None, parameters=None, description=None):
    """A budget's mapping, for deb.load(): lists of entries as in the file
    (dicts, e.g. from flat_source(), modal(), state_space()); a contributor
    may be a (name, source, path) tuple and an output a (name, signal, unit)
    tuple."""
    out = {"name": name}
    if description is not None:
        out["description"] = description
    if parameters is not None:
        out["parameters"] = parameters
    if grid is not None:
        out["grid"] = grid
    out["sources"] = list(sources)
    out["paths"] = list(paths)
    out["contributors"] = [dict(zip(("name", "source", "path"), c)) if isinstance(c, tuple) else c
                           for c in contributors]
    out["outputs"] = [dict(zip(("name", "signal", "unit"), o)) if isinstance(o, tuple) else o for o in outputs]
    if bands is not None:
        out["bands"] = [list(b) if isinstance(b, tuple) else b for b in bands]
    return out


# Measured data from arrays. A budget reads measured spectra and frequency
# responses from files (docs/data_files.md); these write such a file, every
# number with 17 significant digits (the library's own writers keep 10 for a
# PSD), for measured_source() and frf_path() to name.

def _names_row(names, argument):
    for n in names:
        if not n or any(ch in n for ch in ", \t#\n/"):
            raise argument_error(argument, f"{n!r} cannot name a column (no commas, blanks, '#' or '/')")
    return names


def write_spectrum(path, f_hz, psd, *, unit, quantity="psd", channels=None, bins=False):
    """Writes a spectrum file (docs/data_files.md, "Spectrum files"): f_hz
    (n,) in Hz, increasing and > 0; psd (n,) or (n, channels), one-sided
    PSDs in unit^2/Hz (quantity="asd": ASDs in unit/sqrt(Hz)); channels: the
    column names (default ch1, ...); bins=True: the rows are the bins of a
    spectral estimate (held constant over each bin), else read log-log.
    Returns the path, as a str."""
    f = real_array(f_hz, "f_hz", 1)
    s = np.asarray(psd)
    s = real_array(s, "psd", 1 if s.ndim <= 1 else 2)
    if s.ndim == 1:
        s = s[:, None]
    if s.shape[0] != f.size:
        raise argument_error("psd", f"expected {f.size} rows (one per frequency), got shape {s.shape}")
    names = _names_row(_names(channels, s.shape[1], "channels", "ch") if channels is not None
                       else [f"ch{i + 1}" for i in range(s.shape[1])], "channels")
    lines = [f"# unit: {unit}", f"# quantity: {quantity}", "# sides: one"]
    if bins:
        lines.append("# interpolation: bins")
    lines.append(", ".join(["f_hz", *names]))
    lines += [", ".join(repr(float(x)) for x in (f[k], *s[k])) for k in range(f.size)]
    with open(path, "w", encoding="utf-8") as out:
        out.write("\n".join(lines) + "\n")
    return str(path)


def write_frf(path, f_hz, h, *, outputs, inputs):
    """Writes a frequency response table (docs/data_files.md): f_hz (n,) in
    Hz, increasing and > 0; h (n, outputs, inputs), complex, as
    frequency_response() returns it; the entries' real and imaginary parts
    as columns OUTPUT/INPUT.re, .im. Returns the path, as a str."""
    f = real_array(f_hz, "f_hz", 1)
    try:
        hc = np.asarray(h)
    except (TypeError, ValueError) as e:
        raise argument_error("h", f"not an array of numbers ({e})") from None
    if hc.dtype.kind not in "fiuc":
        raise argument_error("h", f"expected complex or real numbers, got dtype {hc.dtype}")
    hc = hc.astype(np.complex128)
    outputs = _names_row([str(n) for n in outputs], "outputs")
    inputs = _names_row([str(n) for n in inputs], "inputs")
    if hc.shape != (f.size, len(outputs), len(inputs)):
        raise argument_error("h", f"expected shape ({f.size}, {len(outputs)}, {len(inputs)}) "
                                  f"(frequencies, outputs, inputs), got {hc.shape}")
    bad = np.argwhere(~np.isfinite(hc))
    if bad.size:
        raise argument_error("h", f"element {tuple(int(i) for i in bad[0])} is {hc[tuple(bad[0])]}; "
                                  "every value must be finite")
    header = ["f_hz"] + [f"{o}/{i}.{part}" for o in outputs for i in inputs for part in ("re", "im")]
    rows = []
    for k in range(f.size):
        cells = [repr(float(f[k]))]
        for a in range(len(outputs)):
            for b in range(len(inputs)):
                cells += [repr(float(hc[k, a, b].real)), repr(float(hc[k, a, b].imag))]
        rows.append(", ".join(cells))
    with open(path, "w", encoding="utf-8") as out:
        out.write(", ".join(header) + "\n" + "\n".join(rows) + "\n")
    return str(path)


def measured_source(name, file=None, *, f_hz=None, psd=None, quantity="psd", unit=None, channels=None,
                    columns=None, extrapolation=None, description=None):
    """A source read from a spectrum file (`type: measured`), e.g. one
    write_spectrum() wrote; or, without a file, from the arrays f_hz (n,)
    and psd (n,) or (n, channels) as write_spectrum() takes them (unit
    required). extrapolation outside the data: "error" (default), "zero"
    or "hold"."""
    if file is None:
        if f_hz is None or psd is None:
            raise argument_error("file", "give a spectrum file, or the arrays f_hz and psd")
        if unit is None:
            raise argument_error("unit", "the unit of the measured arrays is required")
        file = write_spectrum(_data_file("source"), f_hz, psd, unit=unit, quantity=quantity, channels=channels)
    elif f_hz is not None or psd is not None:
        raise argument_error("file", "give a file or the arrays f_hz and psd, not both")
    spectrum = {"type": "measured", "file": str(file)}
    if columns is not None:
        spectrum["columns"] = list(columns)
    if extrapolation is not None:
        spectrum["extrapolation"] = extrapolation
    entry = {"name": name, "spectrum": spectrum}
    if unit is not None:
        entry["unit"] = unit
    if channels is not None:
        entry["channels"] = list(channels)
    if description is not None:
        entry["description"] = description
    return entry


def frf_path(name, file=None, *, f_hz=None, h=None, input_unit, output_unit, inputs=None, outputs=None,
             extrapolation=None, description=None):
    """A path read from a frequency response table (`type: frf`), e.g. one
    write_frf() wrote; or, without a file, from the arrays f_hz (n,) and h
    (n, outputs, inputs) as write_frf() takes them (inputs and outputs then
    name the channels, default u1.. and y1..). inputs/outputs: the names (and
    order) the file must hold (default: all, in the file's order)."""
    if file is None:
        if f_hz is None or h is None:
            raise argument_error("file", "give a frequency response file, or the arrays f_hz and h")
        shape = np.shape(h)
        if len(shape) != 3:
            raise argument_error("h", f"expected (n, outputs, inputs), got shape {shape}")
        outputs = list(outputs) if outputs is not None else [f"y{i + 1}" for i in range(shape[1])]
        inputs = list(inputs) if inputs is not None else [f"u{j + 1}" for j in range(shape[2])]
        file = write_frf(_data_file("path"), f_hz, h, outputs=outputs, inputs=inputs)
    elif f_hz is not None or h is not None:
        raise argument_error("file", "give a file or the arrays f_hz and h, not both")
    entry = {"type": "frf", "file": str(file)}
    if inputs is not None:
        entry["inputs"] = list(inputs)
    if outputs is not None:
        entry["outputs"] = list(outputs)
    if extrapolation is not None:
        entry["extrapolation"] = extrapolation
    return _common(entry, name, description, input_unit, output_unit)
