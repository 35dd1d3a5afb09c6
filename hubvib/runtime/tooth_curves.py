"""Intact FE tooth curves shared on disk by the processes of one FE stage (SI).

Every crack case compares its cracked ring tooth with the same tooth intact, and
the intact curves (planet tooth and ring tooth, per mesh level) are the same for
every case.  Each worker process used to compute them itself; with
:func:`shared_intact_curve` as the FE stage's store
(``fem.tooth_stiffness.set_intact_store``) the first process that needs one computes
it under its lock and writes it as an FE cache entry (``runtime.fe_cache``: keyed on
the body, contact span, material, mesh options, tooth and the source of every hubvib
module this one imports, checked before use); the others wait for that lock and read
it.  The curve read back holds the same floats (JSON keeps every digit of a float).
"""
from __future__ import annotations

from dataclasses import asdict

import numpy as np

from hubvib.fem.tooth_stiffness import ToothCurve
from hubvib.meshing.cache import root_folder
from hubvib.runtime.fe_cache import (CacheEntryError, case_lock, entry_key, finite_positive,
                                     read_entry, write_entry)

#: what an entry holds (part of its key)
QUANTITY = "intact tooth compliance at Chebyshev radii"
#: the entry module of the cached computation (the curve comes from
#: ``fem.tooth_stiffness``, which this module imports): its source key
SOURCE = (__name__,)


def curve_inputs(body, span, material, options, tooth: int) -> dict:
    """Everything that decides one intact curve, as plain data."""
    return {"body": type(body).__name__, "geometry": asdict(body),
            "span_m": [float(r) for r in span], "material": asdict(material),
            "options": asdict(options), "tooth": int(tooth), "quantity": QUANTITY}


def _check(result: dict) -> None:
    radii, compliance = result.get("radii_m"), result.get("compliance_m_N")
    if not (isinstance(radii, list) and isinstance(compliance, list)
            and len(radii) == len(compliance) > 0):
        raise CacheEntryError("radii_m and compliance_m_N must be lists of one length")
    if not isinstance(result.get("dofs"), int) or result["dofs"] <= 0:
        raise CacheEntryError("dofs must be a positive integer")
    finite_positive({f"r{i}": v for i, v in enumerate(radii + compliance)},
                    [f"r{i}" for i in range(2 * len(radii))])


def shared_intact_curve(compute, body, span, material, options, tooth: int) -> ToothCurve:
    """The curve ``compute()`` gives, from the FE cache folder's ``tooth-curves`` entries
    when another process computed it (waiting while it does), else computed here and
    stored (``fem.tooth_stiffness.set_intact_store``)."""
    inputs = curve_inputs(body, span, material, options, tooth)
    path = (root_folder() / "stiffness" / "tooth-curves"
            / f"{entry_key(inputs, modules=SOURCE)}.json")
    with case_lock(path, wait=True):
        try:
            result = read_entry(path, inputs, _check, modules=SOURCE)
        except CacheEntryError:
            curve = compute()
            write_entry(path, inputs, {"radii_m": [float(r) for r in curve.radii],
                                       "compliance_m_N": [float(q) for q in curve.compliance],
                                       "dofs": int(curve.dofs)}, modules=SOURCE)
            return curve
    return ToothCurve(np.array(result["radii_m"]), np.array(result["compliance_m_N"]),
                      int(result["dofs"]))
