"""deb's errors as Python exceptions (raised by the compiled module too)."""


class InputError(ValueError):
    """Bad input: a budget file or text, an override, an argument or an array.

    str(e) is deb's located message, ``file:line:col: key.path: rule``;
    the parts are attributes, each None when not known:

    file      the budget file (or the name given to a text or dict)
    line      1-based line in it
    column    1-based column
    key_path  where in the budget, e.g. ``paths[0].damping``, or the
              argument's name for a Python argument
    message   the rule that was broken, without the location
    """

    def __init__(self, text, *, message=None, file=None, line=None, column=None, key_path=None):
        super().__init__(text)
        self.message = text if message is None else message
        self.file = file
        self.line = line
        self.column = column
        self.key_path = key_path


class WriteError(OSError):
    """A report or result directory that cannot be written."""


def argument_error(argument, message):
    """An InputError about a Python argument: its name is the key path."""
    return InputError(f"{argument}: {message}", message=message, key_path=argument)
