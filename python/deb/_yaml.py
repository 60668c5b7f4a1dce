"""Python values (dicts, lists, numbers, strings, numpy arrays) as YAML text.

A budget given as a dict is written out as YAML and loaded by the same
loader as a file, so that every rule of a budget file applies to it and
its errors name a line and a key path. Numbers are written with 17
significant digits at most (Python's repr: the shortest text that reads back
as the same double); mappings in block
style (a key per line, for the error's line), lists of scalars in flow
style on one line.
"""

import json
import math
import re
from collections.abc import Mapping

import numpy as np


def scalar(value):
    """One scalar as YAML text."""
    if value is None:
        return "null"
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        x = float(value)
        if math.isnan(x):
            return ".nan"  # refused by the loader, at this key
        if math.isinf(x):
            return ".inf" if x > 0 else "-.inf"
        return repr(x)
    if isinstance(value, str):
        # JSON's string syntax is YAML's double-quoted style.
        return json.dumps(value, ensure_ascii=False)
    raise TypeError(f"cannot write {type(value).__name__} into a budget")


_PLAIN_KEY = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


def key(name):
    """A mapping key: plain when it is a word (budget keys, names), else quoted."""
    name = str(name)
    if _PLAIN_KEY.match(name) and name not in ("true", "false", "null", "yes", "no", "on", "off", "y", "n"):
        return name
    return scalar(name)


def _is_scalar(value):
    return not isinstance(value, (Mapping, list, tuple, np.ndarray))


def _flow(value):
    """A list (of lists) of scalars on one line."""
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_flow(v) for v in value) + "]"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{key(k)}: {_flow(v)}" for k, v in value.items()) + "}"
    return scalar(value)


def _only_scalars(value):
    if isinstance(value, np.ndarray):
        return True
    if isinstance(value, (list, tuple)):
        return all(_only_scalars(v) if isinstance(v, (list, tuple, np.ndarray)) else _is_scalar(v) for v in value)
    return False


def _block(value, indent):
    pad = " " * indent
    lines = []
    if isinstance(value, Mapping):
        if not value:
            return [pad + "{}"]
        for k, v in value.items():
            name = key(k)
            if _is_scalar(v) or _only_scalars(v) or (isinstance(v, (Mapping, list, tuple)) and not v):
                lines.append(f"{pad}{name}: {_flow(v)}")
            else:
                lines.append(f"{pad}{name}:")
                lines.extend(_block(v, indent + 2))
        return lines
    if isinstance(value, (list, tuple)):
        for v in value:
            if _is_scalar(v) or _only_scalars(v):
                lines.append(f"{pad}- {_flow(v)}")
            else:
                sub = _block(v, indent + 2)
                lines.append(pad + "- " + sub[0][indent + 2:])
                lines.extend(sub[1:])
        return lines
    return [pad + scalar(value)]


def dump(mapping):
    """The YAML text of a mapping (a budget as a dict)."""
    if not isinstance(mapping, Mapping):
        raise TypeError("a budget is a mapping (dict)")
    return "\n".join(_block(mapping, 0)) + "\n"
