"""The crack as the working load leaves it: frictionless contact of the crack's faces on
the mounted FE ring under the planets' mesh forces, per carrier position (SI units).

The working load is the design's sun torque ``T`` (design file ``load.sun_torque``, the
design field ``sun_torque`` [N m]; the ``[signal]`` table's ``sun_torque_N_m`` is the same
quantity).  With equal load sharing each planet's mesh force on its ring tooth, along the
line of action, is ``F = T / (N r_b,sun)`` [N] (``hubvib.reducer.stages.mesh_force``; the
ring-planet and sun-planet mesh forces of a planet are equal, their base radii' moment
arms aside).  It loads the tooth's load patch as ``F contact[:, k]`` (the unit load along
the line of action, into the tooth).  A reversed torque is taken as ``-F`` on the same
patches: the linear ring sees the same line of action pulled (the opposite flank's patch
is not in the mesh, so this is the reversed load's first approximation).

The faces' contact is condensed onto the crack pairs (``fem.crack_pairs``) with one
factorisation of the ring's stiffness (the one its basis is built with):
``g = g0 + C lam``, ``C = G_n K^-1 G_n^T``, ``g0 = F sum_k H[:, k]`` with
``H = G_n K^-1 contact``, solved by ``fem.signorini``.  With no closure gap the state is
the same at every torque of one sign (the problem is homogeneous of degree one).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.foundation.errors import InputError


class LoadedStateError(InputError):
    """A loaded crack state that cannot be computed; the message names the input."""


@dataclass(frozen=True)
class CrackState:
    """The crack's faces at one carrier position under the working load.

    Attributes
    ----------
    carrier_tooth : int
        Planet 1's ring tooth.
    open_length_m : float
        Crack path with its faces apart [m] (sum of the pairs' path lengths; a pair
        touching without force counts as apart).
    max_gap_m : float
        Largest separation beyond the closure gap, ``max(g - c)`` [m] (0 when closed).
    open_pairs : tuple of bool
        Per crack pair (from the tip): faces apart.
    """

    carrier_tooth: int
    open_length_m: float
    max_gap_m: float
    open_pairs: tuple = ()


@dataclass(frozen=True, eq=False)
class CrackContact:
    """The condensed contact of one cracked ring.

    Attributes
    ----------
    pairs : fem.crack_pairs.CrackPairs
    compliance : ndarray (pairs, pairs)
        ``C = G_n K^-1 G_n^T`` [m/N].
    tooth_opening : ndarray (pairs, z)
        Opening of each pair per 1 N on tooth k's load patch [m/N].
    """

    pairs: object
    compliance: np.ndarray
    tooth_opening: np.ndarray


def crack_contact(body, pairs, response: np.ndarray) -> CrackContact:
    """``response``: ``K^-1 pairs.functionals`` (dofs, 2 pairs) from the ring's one
    factorisation (``fem.ring_basis.RingBasis.functional_response``)."""
    if body.mounting == "free":
        raise LoadedStateError("mounting = free: a free ring under the working load has "
                               "no static state; use mounting foundation or clamped")
    p = pairs.count
    Y = response[:, :p]
    C = np.asarray(pairs.G_n @ Y)
    C = 0.5 * (C + C.T)
    H = np.asarray(body.contact.T @ Y).T
    return CrackContact(pairs, C, H)


def pitch_teeth(teeth: int, n_planets: int, tooth: int) -> tuple:
    """Planet 1's ring tooth at each carrier position over one planet pitch, the carrier
    turning counter-clockwise: the cracked tooth and the next ``ceil(z / N) - 1``."""
    return tuple((tooth + j) % teeth for j in range(math.ceil(teeth / n_planets)))


def crack_state(contact: CrackContact, carrier_tooth: int, engaged_teeth, mesh_force: float,
                closure_gap: float = 0.0):
    """The faces' state with planets on ``engaged_teeth`` each pressing ``mesh_force`` [N]
    along its line of action; ``closure_gap`` [m] >= 0.  Returns (CrackState,
    fem.signorini.ContactSolution)."""
    from hubvib.fem.signorini import signorini

    if not (math.isfinite(closure_gap) and closure_gap >= 0):
        raise LoadedStateError(f"closure_gap = {closure_gap!r} m, allowed >= 0")
    if not math.isfinite(mesh_force):
        raise LoadedStateError(f"mesh_force = {mesh_force!r} N, allowed finite")
    g0 = mesh_force * contact.tooth_opening[:, list(engaged_teeth)].sum(axis=1)
    solution = signorini(contact.compliance, g0 - closure_gap)
    apart = ~solution.pressed  # no pressure: free (touching without force counts as apart)
    length = contact.pairs.length
    return CrackState(int(carrier_tooth), float(length[apart].sum()),
                      float(solution.gap.max(initial=0.0)),
                      tuple(bool(a) for a in apart)), solution
