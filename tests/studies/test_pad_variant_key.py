"""The ``[elastic] pad_variant`` scene key and the stage's reason when it does not run."""
from __future__ import annotations

import pytest

from hubvib.elastic.options import parse_elastic_table
from hubvib.foundation.errors import SceneError


def test_the_key_defaults_off_and_takes_a_bool_only():
    assert parse_elastic_table({}).pad_variant is False
    assert parse_elastic_table({"pad_variant": True}).pad_variant is True
    with pytest.raises(SceneError, match="pad_variant"):
        parse_elastic_table({"pad_variant": "yes"})


def test_the_stage_says_why_it_did_not_run(monkeypatch):
    from dataclasses import replace

    from hubvib.studies import elastic_stage
    from hubvib.studies.elastic_stage import elastic_pad_variant
    from hubvib.studies.scene import load_scene

    scene = load_scene("raba118_crack")
    assert scene.elastic.pad_variant is True, "the default scene's report shows the variant"
    assert elastic_pad_variant(scene, None) == (None, "the elastic ring did not run")
    off = replace(scene.elastic, pad_variant=False)
    monkeypatch.setattr(elastic_stage, "_elastic_scene", lambda s: off)
    assert elastic_pad_variant(scene, object()) == (
        None, "the scene's [elastic] pad_variant is false")
    free = replace(scene.elastic, pad_variant=True,
                   options=replace(scene.elastic.options, mounting="free"))
    monkeypatch.setattr(elastic_stage, "_elastic_scene", lambda s: free)
    variant, reason = elastic_pad_variant(scene, object())
    assert variant is None and "free" in reason
