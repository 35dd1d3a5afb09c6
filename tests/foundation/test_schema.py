"""The declarative table checks (hubvib.foundation.schema): the documented defaults are the
options objects' defaults, every range end is accepted or refused as its interval says, unknown
and missing keys are named, and every key of the generated docs reference is a key the scene
parser accepts (the reference cannot drift from the parser)."""
from __future__ import annotations

import math

import pytest

from hubvib.design.model import MaterialSpec, SupportSpec
from hubvib.design.parse import MATERIAL, SCHEMAS, SUPPORTS, table_design
from hubvib.detection.options import SCHEMA as DETECTION, DetectionOptions
from hubvib.foundation.errors import SceneError
from hubvib.foundation.schema import REQUIRED, Field, Schema
from hubvib.runtime.engines import SCHEMA as EXECUTION, Execution
from hubvib.signal.options import SCHEMA as SIGNAL, SignalOptions
from hubvib.cases.sweep import CrackSweep
from hubvib.studies.crack_table import SCHEMA as CRACK
from hubvib.studies.scene import OUTPUT, REDUCER, STUDY, parse_scene

SCENE_SCHEMAS = (REDUCER, STUDY, OUTPUT, CRACK, DETECTION, SIGNAL, EXECUTION)


@pytest.mark.parametrize("schema, options", [
    (SIGNAL, SignalOptions()), (DETECTION, DetectionOptions()), (EXECUTION, Execution()),
    (CRACK, CrackSweep(depths=(0.0,))), (MATERIAL, MaterialSpec()), (SUPPORTS, None),
], ids=lambda x: getattr(x, "table", ""))
def test_documented_defaults_are_the_options_defaults(schema, options):
    if schema is SUPPORTS:  # SupportSpec's attributes are count, arc, first (radians)
        options = SupportSpec()
        names = {"count": "count", "arc_deg": "arc", "first_deg": "first"}
    else:
        names = {f.key: f.name for f in schema.fields}
    for f in schema.fields:
        # path fills two attributes (angle, path kind: crack_table._path)
        if f.default is REQUIRED or names[f.key] in ("half_lengths", "through_rim", "path"):
            continue
        want = getattr(options, names[f.key])
        got = None if f.default is None else f.convert(f.default)
        if isinstance(want, float):
            assert math.isclose(got, want, rel_tol=1e-15), (
                f"[{schema.table}] {f.key}: documented default {f.default!r} -> {got!r}, "
                f"options default {want!r} (exact up to the unit factor's rounding)")
        else:
            assert got == want, f"[{schema.table}] {f.key}: documented {got!r}, options {want!r}"


def _number_fields():
    for schema in (*SCENE_SCHEMAS, *SCHEMAS):
        for f in schema.fields:
            if f.kind == "number" and f.check is None and f.allowed is None and f.message is None:
                yield pytest.param(schema, f, id=f"{schema.table}.{f.key}")


@pytest.mark.parametrize("schema, field", list(_number_fields()))
def test_range_ends_follow_the_printed_interval(schema, field):
    """Each finite end is accepted iff its bracket is closed, just outside is refused, and the
    refusal names the key, the value and the interval it prints."""
    for end, is_open, outside in ((field.low, field.open_low, -1),
                                  (field.high, field.open_high, 1)):
        if not math.isfinite(end):
            continue
        assert field.accepts(end) is (not is_open), f"{field.key} = {end}: {field.interval()}"
        beyond = end + outside * max(abs(end), 1.0) * 1e-9
        assert not field.accepts(beyond), f"{field.key} = {beyond} outside {field.interval()}"
        with pytest.raises(schema.error) as info:
            schema.value({field.key: beyond}, field.key)
        message = str(info.value)
        assert field.key in message and repr(beyond) in message and field.interval() in message
        assert "\n" not in message
    assert not field.accepts(True) and not field.accepts("1") and not field.accepts(math.nan)


def test_unknown_and_missing_keys_are_named():
    schema = Schema("demo", (Field("a", "integer", 0, 3, default=REQUIRED),
                             Field("b", "bool", default=False)))
    with pytest.raises(SceneError, match=r"^unknown key\(s\) \['c', 'z'\] at \[demo\]; "
                                         r"allowed: \['a', 'b'\]$"):
        schema.parse({"a": 1, "z": 0, "c": 1})
    with pytest.raises(SceneError, match=r"^missing required key\(s\) demo.a$"):
        schema.parse({"b": True})
    assert schema.parse({"a": 3}, defaults=True) == {"a": 3, "b": False}
    with pytest.raises(SceneError, match=r"^\[demo\] a = 4; allowed: an integer in 0..3$"):
        schema.parse({"a": 4})


def test_design_messages_name_the_dotted_key():
    base = {"n_planets": 3, "module": 2.5e-3, "face_width": 0.03, "sun": {"teeth": 20},
            "planet": {"teeth": 31}, "ring": {"teeth": 82, "rim_thickness": 0.012}}
    with pytest.raises(ValueError, match=r"^unknown key\(s\) design.sun.tooth; allowed: bore, "
                                         r"shift, teeth$"):
        table_design({**base, "sun": {"teeth": 20, "tooth": 1}})
    with pytest.raises(ValueError, match=r"^missing required key\(s\) design.bearings.carrier."
                                         r"rollers, design.bearings.carrier.roller_length, "
                                         r"design.bearings.carrier.load$"):
        table_design({**base, "bearings": {"carrier": {}}})
    with pytest.raises(ValueError, match=r"^design.material.nu = 0.5; allowed: a number in "
                                         r"\[-0.99, 0.49\]$"):
        table_design({**base, "material": {"nu": 0.5}})


@pytest.mark.parametrize("schema", SCENE_SCHEMAS, ids=lambda s: s.table)
def test_every_documented_scene_key_is_accepted_by_the_scene_parser(schema):
    """Each key of the generated reference, at its documented default (or a valid value),
    passes ``parse_scene`` in a crack scene: no key is documented that the parser refuses."""
    tables = {"crack": {"depths": [0.0]}}
    valid = {"values": [1e5], "parameter": "c_ru", "parameters": {}, "half_lengths": None,
             "planet_position_errors_m": [0.0, 0.0, 0.0], "pin_hole_radial_errors_m": [0.0] * 3,
             "sensor_angles_from_crack_deg": [90.0], "scheduler": None, "workers": 2}
    for f in schema.fields:
        value = valid.get(f.key, f.default)
        if value is None or f.key in ("parameter", "values"):
            continue
        tables.setdefault(schema.table, {})[f.key] = value
    if schema is EXECUTION:
        tables["execution"]["engine"] = "local"
    text = "\n".join(_toml(name, table) for name, table in tables.items())
    scene = parse_scene(text, "keys")
    assert scene.kind == "crack", f"{schema.table}: {scene.kind}"


def _toml(name, table) -> str:
    def value(v):
        if isinstance(v, bool):
            return str(v).lower()
        if isinstance(v, str):
            return f'"{v}"'
        if isinstance(v, dict):
            return "{}"
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return repr(v)
    return f"[{name}]\n" + "".join(f"{k} = {value(v)}\n" for k, v in table.items())
