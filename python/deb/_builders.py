"""Sources, paths and budgets from numpy arrays, without a file.

Each function returns the dict of one entry of a budget file (a source, a
path) in the file's layout, and deb.budget() the whole mapping; deb.load()
writes it out as YAML and loads it, so every rule of a budget file applies
and an error names the key (paths[0].damping) and the line of that text.
Here only the arrays are checked: numbers, finite, and of the documented
shape, else deb.InputError naming the argument.
"""

import numpy as np

from ._errors import argument_error


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
