"""The elastic ring's detectability against its mounting in the report: the one map
section writer and figure of every ring model (:mod:`hubvib.reports.mounting_map_sections`,
:func:`hubvib.detection.plots.map_figure`), under the names the report calls."""
from __future__ import annotations

from hubvib.reports.mounting_map_sections import map_section, map_summary, map_table

__all__ = ["map_summary", "map_table", "map_section", "map_figure"]


def map_figure(name: str, emap):
    """:func:`hubvib.detection.plots.map_figure` of ``emap`` (an ``ElasticMap`` or its
    ``MountingMap``)."""
    from hubvib.detection.plots import map_figure as figure

    return figure(name, emap)
