"""The elastic ring's figures for the docs: ring modes per family, the crack's changes of
the coupled modes (open, closed, bilinear) on two mesh levels, and the band where the
rigid-ring model holds, for the shipped presets (SI inside; JSON out).

``python -m hubvib.elastic.survey --out docs/data/elastic_ring.json``
"""
from __future__ import annotations

import argparse
import dataclasses
import datetime
import json
import math
from pathlib import Path

import numpy as np

from hubvib.reducer.stages import lumped_parameters
from hubvib.design.presets import preset_design
from hubvib.lumped import natural_modes
from hubvib.meshing.crack import Crack

from .model import elastic_ring, elastic_spectrum
from .options import ElasticOptions, modal_mesh
from .tracking import track_modes

#: root-crack depths as fractions of the path through the rim (Raba 118/76: 6.1, 12.2 mm)
DEPTH_FRACTIONS = (0.25, 0.5)


def bilinear(f_open: float, f_closed: float) -> float:
    """The breathing crack's frequency: open half a cycle, closed the other half (the
    period is the mean of the two half-periods) [Hz]."""
    return 2 * f_open * f_closed / (f_open + f_closed)


def ring_families(er) -> list[dict]:
    """The mounted ring's own modes (no planets) with their nodal diameters."""
    from .content import diameter_content

    basis = er.basis
    phi = basis.V[:, :basis.mode_hz.size]
    out = []
    for j, f in enumerate(basis.mode_hz):
        shares = diameter_content(np.asarray(er.body.probe @ phi[:, j]))
        out.append({"frequency_hz": float(f), "nodal_diameter": int(np.argmax(shares))})
    return out


def validity(design, options: ElasticOptions) -> dict:
    """The computed band where the rigid-ring model holds (``validity.validity_band``: the
    intact coupled spectrum against the rigid model with the same static stiffness) and
    the design's top 9 + 3N mode."""
    from .validity import validity_band, validity_record

    lumped_top = float(natural_modes(lumped_parameters(design)).frequency_hz.max())
    return validity_record(validity_band(design, options)) | {"lumped_top_hz": lumped_top}


def depths(design) -> tuple:
    """The surveyed root-crack depths of ``design`` [m] (``DEPTH_FRACTIONS`` of the path
    through the rim, rounded to 0.1 mm)."""
    from hubvib.reducer.stages import ring_gear

    through = Crack(depth=1e-4).through_depth(ring_gear(design))
    return tuple(round(f * through, 4) for f in DEPTH_FRACTIONS)


def crack_changes(design, options: ElasticOptions) -> dict:
    """Coupled modes intact and per depth (open and closed faces) with tracking."""
    intact_ring = elastic_ring(design, options=options)
    intact = elastic_spectrum(intact_ring)
    mass = float(intact_ring.body.rigid_mass()[0, 0])
    out = {"intact": [dict(r) for r in intact.rows()], "depths_mm": [], "dofs":
           intact_ring.body.ndofs}
    for depth in depths(design):
        per = {}
        for closed in (False, True):
            spec = elastic_spectrum(elastic_ring(design, Crack(depth=depth), closed, options,
                                                 intact_ring.carrier_teeth))
            tracked = track_modes(intact, spec, mass)
            per["closed" if closed else "open"] = (spec, tracked)
        rows = []
        for i, row in enumerate(intact.rows()):
            entry = {"mode": row["mode"], "intact_hz": row["frequency_hz"]}
            for key, (spec, tracked) in per.items():
                ref = np.array(tracked.reference)
                j = np.flatnonzero(ref == i)
                entry[f"{key}_hz"] = float(spec.frequency_hz[j[0]]) if j.size else None
                entry[f"{key}_split_pair"] = bool(tracked.split_pair[j[0]]) if j.size else False
            if entry["open_hz"] is not None and entry["closed_hz"] is not None:
                entry["bilinear_hz"] = bilinear(entry["open_hz"], entry["closed_hz"])
            rows.append(entry)
        out["depths_mm"].append({"depth_mm": 1e3 * depth, "modes": rows})
    return out


def survey(presets=("raba118", "hub4")) -> dict:
    data = {"measured": datetime.datetime.now(datetime.timezone.utc).strftime(
        "%Y-%m-%d %H:%M UTC"), "designs": {}}
    for name in presets:
        design = preset_design(name)
        options = ElasticOptions()
        coarse = crack_changes(design, options)
        fine_mesh = modal_mesh()
        fine_mesh = dataclasses.replace(fine_mesh, size=fine_mesh.size / math.sqrt(2),
                                        tooth_size=fine_mesh.tooth_size / math.sqrt(2),
                                        load_size=fine_mesh.load_size / math.sqrt(2))
        fine = crack_changes(design, ElasticOptions(mesh=fine_mesh))
        er = elastic_ring(design, options=options)
        free = elastic_ring(design, options=ElasticOptions(mounting="free"))
        clamped = elastic_ring(design, options=ElasticOptions(mounting="clamped"))
        data["designs"][name] = {
            "families_mounted": ring_families(er), "families_free": ring_families(free),
            "families_clamped": ring_families(clamped),
            "foundation_N_m2": {"normal": er.foundation.k_n, "tangential": er.foundation.k_t},
            "k_rest_N_m": er.k_rest, "validity": validity(design, options),
            "coarse": coarse, "fine": fine,
            "mesh_sizes_m": [dataclasses.asdict(options.mesh), dataclasses.asdict(fine_mesh)],
        }
    return data


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args(argv)
    args.out.write_text(json.dumps(survey(), indent=1, allow_nan=False) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
