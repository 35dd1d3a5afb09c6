"""``hubvib design check FILE.toml``: what follows from a design, or every rule it breaks."""
from __future__ import annotations

import json
import math
from pathlib import Path

from hubvib.design import PRESETS, preset_design, preset_names


def add_parser(sub) -> None:
    p = sub.add_parser("design", help="check a reducer design file (assembly rules, derived "
                       "geometry and lumped fields)")
    p.add_argument("action", choices=["check"])
    p.add_argument("file", help="design TOML file, or the name of a preset design "
                   f"({', '.join(preset_names())})")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def design_from_argument(text: str):
    """A design file path, or the name of a preset design."""
    from hubvib.reducer import load_design  # the FE stage's geometry: loaded when used

    path = Path(text)
    if not path.exists() and text in PRESETS:
        return preset_design(text)
    return load_design(path)


def run(args) -> int:
    from hubvib.reducer import summary

    info = summary(design_from_argument(args.file))
    if args.json:
        print(json.dumps(info, indent=2, allow_nan=False))
        return 0
    print(f"design {info['name']!r}: assembles")
    print(f"  planets: {info['n_planets']} at "
          f"{', '.join(f'{a:.4g}' for a in info['planet_angles_deg'])} deg"
          f"{' (equally spaced)' if info['equally_spaced'] else ''}")
    print(f"  centre distance {1e3 * info['centre_distance_m']:.4f} mm (both pairs); working "
          f"pressure angles sun-planet {info['working_pressure_angle_sun_planet_deg']:.4f} deg, "
          f"ring-planet {info['working_pressure_angle_ring_planet_deg']:.4f} deg")
    print(f"  contact ratios: sun-planet {info['contact_ratio_sun_planet']:.4f}, ring-planet "
          f"{info['contact_ratio_ring_planet']:.4f}; ratio carrier/sun "
          f"1 : {info['ratio_carrier_to_sun']:.4g}")
    print(f"  ring: outer diameter {1e3 * info['ring_outer_diameter_m']:.3f} mm, rim "
          f"{1e3 * info['ring_rim_thickness_m']:.3f} mm below the root circle")
    print("  lumped fields (SI): the value the lumped model uses and how it is obtained")
    units = {"d": "m", "m": "kg", "mu": "kg", "c": "N/m", "alpha": "rad"}
    for key, row in info["lumped"].items():
        unit = units[key.split("_")[0]]
        value = f"{row['value']:.6g} {unit}"
        if unit == "rad":
            value += f" ({math.degrees(row['value']):.4f} deg)"
        method = row["method"]
        if "geometry_value" in row:
            method += f"; {row['geometry_method']} gives {row['geometry_value']:.6g} {unit}"
        print(f"    {key:<8} {value:<30} {method}")
    if info["lumped_missing"]:
        print("  the lumped model still needs (design.lumped or design.bearings): "
              + ", ".join(info["lumped_missing"]))
    for note in info["notes"]:
        print(f"  note: {note}")
    return 0
