"""Declarative checks of TOML tables: a table is a tuple of fields, each one line.

A :class:`Field` is a key with its kind (number, integer, choice, bool, string, list of
numbers), its allowed range or choices, its documented default, its unit, a line of doc,
the attribute it fills and the factor from its edge unit to SI.  A :class:`Schema` is a
table's fields plus how its messages read; ``Schema.parse(table)`` refuses unknown and
missing keys and every value outside its field's range with one line naming the key, the
value and what is allowed, and returns ``{attribute: value in SI}`` for the keys given.
The docs' key tables are generated from the same fields (``Schema.rows``), so the
reference cannot drift from the parser.

Why in-house (docs/architecture.md): the messages users and tests read today (about 90
asserted) are kept byte for byte, each table with its own wording; pydantic or jsonschema
would validate the same ranges but phrase every refusal their own way, so each message
would need a rewriting layer of about the size of this module.  Standard library only.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

from .errors import SceneError

#: ``Field.default`` of a key that must be given
REQUIRED = object()
KINDS = ("number", "integer", "choice", "bool", "string", "numbers", "table")


@dataclass(frozen=True)
class Field:
    """One key of a TOML table.

    ``kind`` is one of ``KINDS``; numbers (and each value of ``numbers``) are finite and
    lie in ``low``..``high`` (``open_low``/``open_high``: the end is excluded); integers in
    ``low..high``; a choice among ``choices``; ``numbers`` is a list of ``sizes[0]`` to
    ``sizes[1]`` numbers.  ``default`` is the documented value at the edge (``REQUIRED``:
    the key must be given), ``unit`` its edge unit, ``scale`` the factor from that unit to
    SI, ``attr`` the attribute it fills (default ``key``).  ``allowed`` replaces the
    generated "allowed" text, ``message`` the table's message template and ``check`` (a
    predicate) the kind's test of the value.
    """

    key: str
    kind: str
    low: float = -math.inf
    high: float = math.inf
    open_low: bool = False
    open_high: bool = False
    choices: tuple = ()
    default: Any = None
    unit: str = ""
    doc: str = ""
    attr: str | None = None
    scale: float = 1.0
    sizes: tuple[int, int] = (1, 12)
    allowed: str | None = None
    message: str | None = None
    check: Callable[[Any], bool] | None = None

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"field {self.key!r}: kind {self.kind!r}; allowed: {KINDS}")

    @property
    def name(self) -> str:
        """The attribute the key fills."""
        return self.attr or self.key

    def _in_range(self, v) -> bool:
        return ((self.low < v if self.open_low else self.low <= v)
                and (v < self.high if self.open_high else v <= self.high))

    def _number(self, v) -> bool:
        return (not isinstance(v, bool) and isinstance(v, (int, float)) and math.isfinite(v)
                and self._in_range(v))

    def accepts(self, v) -> bool:
        """Whether ``v`` is an allowed value of this key."""
        if self.check is not None:
            return self.check(v)
        if self.kind == "number":
            return self._number(v)
        if self.kind == "integer":
            return not isinstance(v, bool) and isinstance(v, int) and self._in_range(v)
        if self.kind == "choice":
            return v in self.choices
        if self.kind == "bool":
            return isinstance(v, bool)
        if self.kind == "string":
            return isinstance(v, str)
        if self.kind == "table":
            return isinstance(v, dict)
        return (isinstance(v, list) and self.sizes[0] <= len(v) <= self.sizes[1]
                and all(self._number(x) for x in v))

    def convert(self, v):
        """The value in SI, as the options object holds it."""
        if self.kind == "number":
            return float(v) * self.scale if self.scale != 1.0 else float(v)
        if self.kind == "numbers":
            return tuple(float(x) for x in v)
        return v

    def interval(self) -> str:
        """``(0, 0.05]``-style range of the field."""
        return (f"{'(' if self.open_low else '['}{self.low:g}, {self.high:g}"
                f"{')' if self.open_high else ']'}")


@dataclass(frozen=True)
class Schema:
    """A TOML table's fields and how its messages read.

    Templates (``str.format``): ``label`` of a key (``{table}``, ``{key}``);
    ``message`` of a refused value (``{label}``, ``{value}`` the value's repr,
    ``{allowed}``); ``unknown`` (``{keys}``, ``{allowed}``: sorted lists; ``{labels}``,
    ``{names}``: the same joined with ", ", ``labels`` each as ``{table}.{key}``) and
    ``missing`` (``{labels}``).  ``number``: the noun of number ranges; ``integers``:
    ``"dots"`` (``1..50``) or ``"interval"`` (``[1, 50]``).  ``error``: the exception
    raised.
    """

    table: str
    fields: tuple[Field, ...]
    error: type = SceneError
    label: str = "[{table}] {key}"
    message: str = "{label} = {value}; allowed: {allowed}"
    unknown: str = "unknown key(s) {keys} at [{table}]; allowed: {allowed}"
    missing: str = "missing required key(s) {labels}"
    number: str = "a number"
    integers: str = "dots"
    by_key: dict = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "by_key", {f.key: f for f in self.fields})

    def allowed(self, f: Field) -> str:
        """What ``f`` accepts, as the messages say it."""
        if f.allowed is not None:
            return f.allowed
        if f.kind == "number":
            return f"{self.number} in {f.interval()}"
        if f.kind == "integer":
            if self.integers == "interval":
                return f"an integer in {f.interval()}"
            return f"an integer in {f.low}..{f.high}"
        if f.kind == "choice":
            return ", ".join(f.choices)
        if f.kind == "bool":
            return "true or false"
        if f.kind == "string":
            return "a string"
        if f.kind == "table":
            return "a table"
        return (f"a list of {f.sizes[0]} to {f.sizes[1]} numbers in [{f.low:g}, {f.high:g}]"
                f"{' ' + f.unit if f.unit else ''}")

    def refuse(self, f: Field, value, table: str | None = None):
        """The error for ``value`` of field ``f`` (to raise)."""
        label = self.label.format(table=table or self.table, key=f.key)
        return self.error((f.message or self.message).format(
            label=label, value=repr(value), allowed=self.allowed(f)))

    def check_keys(self, table: dict, name: str | None = None) -> None:
        """Refuse unknown keys, then missing required ones."""
        name = name or self.table
        unknown = sorted(set(table) - set(self.by_key))
        if unknown:
            allowed = sorted(self.by_key)
            raise self.error(self.unknown.format(
                keys=unknown, allowed=allowed, table=name,
                labels=", ".join(f"{name}.{k}" for k in unknown), names=", ".join(allowed)))
        missing = [f.key for f in self.fields if f.default is REQUIRED and f.key not in table]
        if missing:
            raise self.error(self.missing.format(
                labels=", ".join(f"{name}.{k}" for k in missing), table=name))

    def parse(self, table: dict, name: str | None = None, defaults: bool = False) -> dict:
        """``{attribute: SI value}`` of the keys given (with ``defaults``, also the
        documented defaults of the keys absent), every key checked in field order."""
        self.check_keys(table, name)
        values = {}
        for f in self.fields:
            if f.key in table:
                if not f.accepts(table[f.key]):
                    raise self.refuse(f, table[f.key], name)
                values[f.name] = f.convert(table[f.key])
            elif defaults and f.default is not REQUIRED:
                values[f.name] = f.default if f.default is None else f.convert(f.default)
        return values

    def value(self, table: dict, key: str, name: str | None = None):
        """One key's SI value (its default when absent), checked."""
        f = self.by_key[key]
        if key not in table:
            return None if f.default is None else f.convert(f.default)
        if not f.accepts(table[key]):
            raise self.refuse(f, table[key], name)
        return f.convert(table[key])

    def rows(self) -> list[list[str]]:
        """One Markdown row per key (the docs' key reference): key, default, allowed, unit,
        doc."""
        def default(f):
            if f.default is REQUIRED:
                return "required"
            if f.default is None:
                return "-"
            if isinstance(f.default, bool):
                return str(f.default).lower()
            if isinstance(f.default, str):
                return f'"{f.default}"'
            return f"{f.default!r}" if isinstance(f.default, (list, tuple)) else f"{f.default:g}"

        def cell(text: str) -> str:  # Markdown: no table cell break, no link reference
            return text.replace("|", "\\|").replace("[", "\\[").replace("]", "\\]")
        return [[f"`{f.key}`", cell(default(f)), cell(self.allowed(f)), cell(f.unit or "-"),
                 cell(f.doc)] for f in self.fields]
