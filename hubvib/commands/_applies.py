"""Flags that apply only to some inputs: given where they would change nothing, they are
refused (one line naming the flag and what it needs), never silently ignored.

A flag checked here has the default ``None`` in its parser, so that "given" can be told
from "left at its default"; :func:`value` supplies the default afterwards."""
from __future__ import annotations

from hubvib.foundation.errors import InputError


class FlagError(InputError):
    """A flag given where it does not apply; the message names it and what it needs."""


def refuse_ignored(args, rules) -> None:
    """``FlagError`` for the first rule ``(flag, applies, needs)`` whose flag was given
    (not ``None``) although ``applies`` is false; ``needs`` says when it applies."""
    for flag, applies, needs in rules:
        given = getattr(args, _attribute(flag))
        if given is not None and not applies:
            shown = flag if given is True else f"{flag} = {given!r}"  # a switch: its name
            raise FlagError(f"{shown} applies only {needs}; drop it")


def refuse_outside(flag: str, given, low: int, high: int, meaning: str) -> None:
    """``FlagError`` naming ``flag`` and its allowed range ``low..high`` (``meaning`` says
    what the range is) when the integer ``given`` lies outside it."""
    if given is not None and not low <= given <= high:
        raise FlagError(f"{flag} = {given!r}, allowed {low}..{high} ({meaning})")


def value(args, flag: str, default):
    """The flag's value, or ``default`` when it was not given."""
    given = getattr(args, _attribute(flag))
    return default if given is None else given


def _attribute(flag: str) -> str:
    return flag.lstrip("-").replace("-", "_")
