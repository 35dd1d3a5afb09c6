"""``hubvib scenes``: the shipped scenes, one line each (``hubvib run NAME`` runs one)."""
from __future__ import annotations

import json


def add_parser(sub) -> None:
    p = sub.add_parser("scenes", help="list the shipped scenes (run one with hubvib run NAME)")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.studies.scene import DEFAULT_SCENE, shipped_scenes

    scenes = shipped_scenes()
    if args.json:
        print(json.dumps({"default": DEFAULT_SCENE, "scenes": scenes}, indent=2))
        return 0
    width = max(map(len, scenes))
    for name, what in scenes.items():
        print(f"{name:<{width}}  {what}{'  (default)' if name == DEFAULT_SCENE else ''}")
    return 0
