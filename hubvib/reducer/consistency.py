"""Lumped parameters that contradict their design are refused, wherever they come from
(a scene's ``[reducer.parameters]``, ``--set`` after ``--design``): the planet count and
angles, and the fields that follow from the geometry (base diameters, working angles)."""
from __future__ import annotations

import math

from hubvib.reducer.stages import derived_lumped_fields
from hubvib.foundation.errors import InputError
from hubvib.lumped import field_names

#: lumped fields that follow from the design's geometry
GEOMETRIC = ("d_s", "d_c", "d_r", "d_p", "alpha_s", "alpha_r")


def check_consistent(design, params, source: str, error=InputError) -> None:
    """Raise ``error`` naming ``source`` (where the parameters came from) when ``params``
    contradicts ``design``: planet count, planet angles [rad] (to 1e-9), or one of the
    ``GEOMETRIC`` fields (to 1e-9 relative) the design gives or derives."""
    if design is None:
        return
    n = len(params.theta)
    if n != design.n_planets:
        raise error(f"{source}: {n} planets, but the design {design.name!r} has "
                    f"n_planets = {design.n_planets}; the planets follow from the design")
    for i, (a, b) in enumerate(zip(params.theta, design.angles)):
        if abs(math.remainder(a - b, 2 * math.pi)) > 1e-9:
            raise error(f"{source}: planet {i + 1} at {math.degrees(a):.6g} deg, but the "
                        f"design {design.name!r} puts it at {math.degrees(b):.6g} deg")
    given = design.lumped_fields
    derived = derived_lumped_fields(design, skip=set(field_names()) - set(GEOMETRIC))
    for key in GEOMETRIC:
        expected = given.get(key, derived.get(key))
        value = getattr(params, key)
        if expected is not None and abs(value - expected) > 1e-9 * abs(expected):
            raise error(f"{source}: {key} = {value:.9g}, but the design {design.name!r} "
                        f"gives {key} = {expected:.9g} (it follows from the geometry; change "
                        f"the design instead)")
