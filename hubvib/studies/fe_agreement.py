"""The plane crack cases as the crack study now computes them (the ring by substructures,
three-level error bars) against the figures the whole-ring path published with its
two-level bars: old value, new value, old bar, new bar of each (SI units).

``python -m hubvib.studies.fe_agreement PUBLISHED.json --out OUT.json`` reads the ``stiffness``
rows of a crack scene's ``results.json`` (the whole-ring path wrote them), recomputes
each depth's case (``fem.estimate.estimate_crack_case``, the ring by substructures) and
writes one row per depth and quantity: whether the move lies within the larger of the
two bars (``within``), the rule of the new bar (``fem.three_level``).
"""
from __future__ import annotations

import json
from pathlib import Path

#: quantity -> (estimate field, published key, published error key)
QUANTITIES = {"c_ru_N_m": ("c_ru", "fe_c_ru_N_m", "fe_c_ru_error_N_m"),
              "c_r_N_m": ("c_r", "fe_c_r_N_m", "fe_c_r_error_N_m"),
              "c_rp_engaged_ratio": ("c_rp_engaged_ratio", "fe_c_rp_engaged_ratio",
                                     "fe_c_rp_engaged_ratio_error")}


def agreement_row(depth_mm: float, quantity: str, old: float, old_error: float,
                  estimate) -> dict:
    """One row: the published ``old`` value with its bar against the ``estimate``
    (``fem.estimate.CrackCaseEstimate``) of the same depth."""
    field = QUANTITIES[quantity][0]
    new, bar = getattr(estimate, field), estimate.error_of(field)
    change, larger = abs(new - old), max(old_error, bar.error)
    return {"depth_mm": depth_mm, "quantity": quantity, "old": old, "new": new,
            "old_error": old_error, "new_error": bar.error, "new_rule": bar.rule,
            "new_order": None if bar.order != bar.order else bar.order,
            "in_old_errors": change / old_error if old_error else None,
            "in_larger_errors": change / larger if larger else None,
            "within": change <= larger}


def agreement_rows(published: dict, design=None) -> list[dict]:
    """One row per depth of ``published`` (a crack scene's results) and quantity
    (``agreement_row``)."""
    from hubvib.reducer.stages import gear_body, material, ring_gear
    from hubvib.design import preset_design
    from hubvib.fem.estimate import estimate_crack_case
    from hubvib.meshing.crack import Crack
    from hubvib.meshing.ring_pieces import ring_pieces
    from hubvib.cases.sweep import ACCURACY

    design = design or preset_design("raba118")
    crack = published["crack"]
    scale = ACCURACY[crack["accuracy"]]
    rows = []
    for row in published["stiffness"]:
        depth = row["depth_mm"] / 1e3
        estimate = estimate_crack_case(
            ring_gear(design), gear_body(design, "planet"),
            Crack(crack["tooth"], depth, crack["angle"], crack["start"]), scale,
            mesher=ring_pieces, material=material(design), n_planets=design.n_planets)
        for name, (_, old_key, error_key) in QUANTITIES.items():
            rows.append(agreement_row(row["depth_mm"], name, row[old_key], row[error_key],
                                      estimate))
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
