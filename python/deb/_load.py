"""deb.load: a budget from a file, a YAML text or a dict, with overrides."""

import os
from collections.abc import Mapping

from . import _deb, _yaml
from ._errors import argument_error


def is_text(source):
    """A str is YAML text when it has a line break or is a flow mapping; else a file name."""
    return "\n" in source or source.lstrip().startswith("{")


def overrides(set):
    """set= as [(key_path, value_text)]: a mapping {key path or parameter: value}, or
    a list of "KEY.PATH=VALUE" strings (the CLI's --set). Values that are not str
    are written as YAML (numbers with round-trip precision, lists, maps); a str is
    the CLI's VALUE as it is ("100 mm", "VC-C", "[0, 50]")."""
    if set is None:
        return []
    if isinstance(set, Mapping):
        items = set.items()
    elif isinstance(set, (list, tuple)):
        items = []
        for entry in set:
            if not isinstance(entry, str) or "=" not in entry:
                raise argument_error("set", f"{entry!r} is not KEY.PATH=VALUE")
            k, v = entry.split("=", 1)
            items.append((k, v))
    else:
        raise argument_error("set", "expected a dict {key path: value} or a list of 'KEY.PATH=VALUE'")
    out = []
    for k, v in items:
        out.append((str(k), v if isinstance(v, str) else _yaml._flow(v)))
    return out


def source_text(source, name=None):
    """(text, name, base_dir) of a text or a dict, or None for a file name."""
    if isinstance(source, Mapping):
        return _yaml.dump(source), name or "<dict>", "."
    if isinstance(source, str) and is_text(source):
        return source, name or "<text>", "."
    return None


def load(source, set=None, *, name=None, base_dir=None):
    """A budget (deb.Budget), loaded and checked as `deb run` loads a file.

    source    a budget file (str or os.PathLike), a YAML text (a str with a line
              break, or a flow mapping "{...}"), or a dict in the file's layout
              (written out as YAML and loaded as text)
    set       overrides applied before loading, as the CLI's --set: a dict
              {"Kv": 60, "sources[0].spectrum.class": "VC-C"} or a list of
              "KEY.PATH=VALUE" strings
    name      how messages name a text or a dict (default "<text>", "<dict>")
    base_dir  where a text's or a dict's relative data-file names are found
              (default: the current directory)

    Raises deb.InputError for anything the budget breaks, located.
    """
    if isinstance(source, _deb.Budget):
        if set:
            source = source.file if source.file is not None else source.text
        else:
            return source
    pairs = overrides(set)
    text = source_text(source, name)
    if text is not None:
        return _deb.load_text(text[0], text[1], base_dir or text[2], pairs)
    if isinstance(source, (str, os.PathLike)):
        return _deb.load_file(os.fspath(source), pairs)
    raise argument_error("source", f"expected a file name, a YAML text or a dict, got {type(source).__name__}")


def budget_of(source, set=None):
    """A deb.Budget as it is, else load(source, set)."""
    if isinstance(source, _deb.Budget) and not set:
        return source
    return load(source, set)
