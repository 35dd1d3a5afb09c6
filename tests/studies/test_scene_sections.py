"""The registry of optional scene sections: each registered once, a scene without the
table gets the section's one default, an unknown name is refused in one line."""
from dataclasses import replace

import pytest

from hubvib.detection.options import DetectionOptions, detection_options
from hubvib.elastic.options import ElasticScene
from hubvib.runtime.engines import Execution
from hubvib.signal.options import SignalOptions
from hubvib.studies.scene import TOP_LEVEL, load_scene, parse_scene
from hubvib.studies.sections import SECTIONS, SceneSection, register_section

EXPECTED = {"detection": DetectionOptions, "execution": Execution, "signal": SignalOptions,
            "elastic": ElasticScene}

SCENE = """
[study]
parameter = "c_ru"
values = [5e5]
"""


def test_every_section_registered_once_with_its_default_type():
    assert set(SECTIONS) == set(EXPECTED)
    assert set(SECTIONS) <= TOP_LEVEL
    for name, section in SECTIONS.items():
        assert section.name == name
        assert isinstance(section.default, EXPECTED[name]), name
    with pytest.raises(ValueError, match="'detection' is registered already"):
        register_section(SceneSection("detection", SECTIONS["detection"].parse, None))
    assert set(SECTIONS) == set(EXPECTED)


def test_a_missing_table_gives_the_section_default():
    scene = parse_scene(SCENE, "t")
    assert scene.tables == {}
    for name in SECTIONS:
        if name == "signal":  # the default with the design's working torque
            assert scene.section(name) == replace(
                SECTIONS[name].default, sun_torque_N_m=scene.design.sun_torque)
        else:
            assert scene.section(name) is SECTIONS[name].default, name
        assert scene.given(name) is None, name
    assert scene.detection == DetectionOptions()
    assert scene.execution == Execution()
    assert scene.signal == SignalOptions()
    assert scene.elastic == ElasticScene()
    assert detection_options(scene) is scene.detection


def test_a_given_table_is_parsed_into_its_section():
    scene = parse_scene(SCENE + "[execution]\nworkers = 3\n[detection]\nseed = 7\n", "t")
    assert scene.execution == Execution(workers=3)
    assert scene.given("execution") is scene.execution
    assert scene.detection.seed == 7
    assert scene.given("signal") is None
    shipped = load_scene(None)
    assert replace(shipped, tables={}).detection is SECTIONS["detection"].default


def test_an_unknown_section_is_refused_in_one_line():
    scene = parse_scene(SCENE, "t")
    for ask in (scene.section, scene.given):
        with pytest.raises(ValueError) as info:
            ask("crack")
        message = str(info.value)
        assert "\n" not in message
        assert message == ("unknown scene section 'crack'; registered: detection, elastic, "
                           "execution, signal")


def test_the_sun_torque_is_one_quantity_the_designs(tmp_path):
    """``[signal] sun_torque_N_m`` repeats the design's ``load.sun_torque`` or is refused
    naming both; absent, the signal runs at the design's torque."""
    from hubvib.foundation.errors import SceneError

    base = '[reducer]\npreset = "raba118"\n[study]\nparameter = "c_ru"\nvalues = [5e5]\n'
    same = tmp_path / "same.toml"
    same.write_text(base + "[signal]\nsun_torque_N_m = 1000.0\n")
    assert load_scene(same).signal.sun_torque_N_m == load_scene(same).design.sun_torque
    other = tmp_path / "other.toml"
    other.write_text(base + "[signal]\nsun_torque_N_m = 500.0\n")
    with pytest.raises(SceneError, match=r"sun_torque_N_m = 500.0 N m, but the design's sun "
                                         r"torque \(load.sun_torque\) is 1000 N m"):
        load_scene(other)
    hub4 = load_scene("hub4_crack_elastic")
    assert hub4.given("signal") is None
    assert hub4.signal.sun_torque_N_m == hub4.design.sun_torque, \
        "no [signal] table: the records run at the design's torque too"
