"""The elastic map runs over the elastic answer's depths, those added to resolve its
crossing included."""
from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace


def test_the_map_takes_the_refined_answers_depths(monkeypatch):
    from hubvib.detection import mounting_map
    from hubvib.studies import elastic_stage
    from hubvib.studies.scene import load_scene

    scene = load_scene("raba118_crack")
    on = replace(scene.elastic, map=True)
    monkeypatch.setattr(elastic_stage, "_elastic_scene", lambda s: on)
    seen = {}

    class Recorded:
        def __init__(self, design, depths, *args, **kwargs):
            seen["depths"] = depths

        def mounting_map(self, options):
            return "map"

    monkeypatch.setattr(mounting_map, "ElasticMounting", Recorded)
    refined = (0.0, 0.0005, 0.00075, 0.003, 0.006)
    elastic = SimpleNamespace(depths=refined, detail=SimpleNamespace(k_rest=2e9))
    assert elastic_stage.elastic_map_of(scene, elastic) == "map"
    assert seen["depths"] == refined, "the map's depths are the refined answer's"
    assert 0.0005 not in elastic_stage.elastic_depths(scene.crack), (
        "the added depths are not the sweep's: the check above means something")
    off = replace(scene.elastic, map=False)
    monkeypatch.setattr(elastic_stage, "_elastic_scene", lambda s: off)
    assert elastic_stage.elastic_map_of(scene, elastic) is None
