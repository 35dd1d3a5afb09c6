"""The plane crack cases by substructures against the published whole-ring figures: old
value, new value and the old error bar of each (SI units).

``python -m hubvib.studies.fe_agreement PUBLISHED.json --out OUT.json`` reads the ``stiffness``
rows of a crack scene's ``results.json`` (the whole-ring path wrote them), recomputes
each depth's case (``fem.estimate.estimate_crack_case``, the ring by substructures) and
writes one row per depth and quantity.
"""
from __future__ import annotations

import json
from pathlib import Path

#: quantity -> (estimate field, published key, published error key)
QUANTITIES = {"c_ru_N_m": ("c_ru", "fe_c_ru_N_m", "fe_c_ru_error_N_m"),
              "c_r_N_m": ("c_r", "fe_c_r_N_m", "fe_c_r_error_N_m"),
              "c_rp_engaged_ratio": ("c_rp_engaged_ratio", "fe_c_rp_engaged_ratio",
                                     "fe_c_rp_engaged_ratio_error")}


def agreement_rows(published: dict, design=None) -> list[dict]:
    """One row per depth of ``published`` (a crack scene's results) and quantity: depth
    [mm], quantity, old, new, the old and the new error estimate, and |new - old| over the
    old error (None where the old error is 0: the intact ratio, 1 by definition)."""
    from hubvib.reducer.stages import gear_body, material, ring_gear
    from hubvib.design import preset_design
    from hubvib.fem.estimate import estimate_crack_case
    from hubvib.meshing.crack import Crack
    from hubvib.meshing.ring_pieces import ring_pieces

    design = design or preset_design("raba118")
    crack = published["crack"]
    scale = {"default": 1.0, "fast": 2.0}[crack["accuracy"]]
    rows = []
    for row in published["stiffness"]:
        depth = row["depth_mm"] / 1e3
        estimate = estimate_crack_case(
            ring_gear(design), gear_body(design, "planet"),
            Crack(crack["tooth"], depth, crack["angle"], crack["start"]), scale,
            mesher=ring_pieces, material=material(design), n_planets=design.n_planets)
        for name, (field, old_key, error_key) in QUANTITIES.items():
            old, bar = row[old_key], row[error_key]
            new = getattr(estimate, field)
            rows.append({"depth_mm": row["depth_mm"], "quantity": name, "old": old, "new": new,
                         "old_error": bar, "new_error": getattr(estimate, f"{field}_error"),
                         "in_old_errors": abs(new - old) / bar if bar else None})
    return rows


def main(argv=None) -> int:
    import argparse

    from hubvib.foundation.output import write_json

    parser = argparse.ArgumentParser(prog="python -m hubvib.studies.fe_agreement")
    parser.add_argument("published", type=Path, help="a crack scene's results.json")
    parser.add_argument("--out", type=Path, required=True, help="the JSON to write")
    args = parser.parse_args(argv)
    data = json.loads(args.published.read_text())
    write_json(args.out, {"published": str(args.published), "date": data.get("date"),
                          "rows": agreement_rows(data)})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
