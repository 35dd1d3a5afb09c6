"""The base of the errors that mean bad input, and the scene's error, which every layer
that parses a scene table raises (the CLI turns any of them into one line
``hubvib: error: ...`` and exit code 2)."""


class InputError(ValueError):
    """Bad input: the message names the key, flag or file, the value and the allowed range."""


class SceneError(InputError):
    """A scene file or one of its tables that cannot be run; the message names the key,
    the value and the allowed range."""
