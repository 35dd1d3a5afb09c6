"""The ring's surfaces as a crack sees them: the toothed inner boundary around a tooth
as segments, the distance of a point to the surfaces, where a ray leaves the body (SI)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .gear import rotation
from .ring_gear import RingGear

INVOLUTE_POINTS = 32  # spline points per involute piece (here and in the ring mesh)
FILLET_POINTS = 48    # spline points per fillet piece


def tooth_outline(ring: RingGear, tooth: int) -> np.ndarray:
    """The toothed inner boundary of one tooth pitch [m], (n, 2): from the middle of the
    space before tooth ``tooth`` over its -psi root land, fillet and flank, tip, +psi
    flank, fillet and root land to the middle of the next space."""
    prof, gear = ring.profile, ring.gear
    flank = gear.flank(np.linspace(prof.tip_radius, prof.form_radius, 4 * INVOLUTE_POINTS))
    fillet = prof.fillet_points(np.linspace(1.0, 0.0, 2 * FILLET_POINTS))
    land_from = math.atan2(fillet[-1, 1], fillet[-1, 0])
    land = prof.root_radius * np.column_stack(
        [np.cos(a := np.linspace(land_from, prof.space_angle, 24)), np.sin(a)])
    positive = np.vstack([flank, fillet[1:], land[1:]])  # tip -> middle of the space
    negative = (positive * np.array([1.0, -1.0]))[::-1]
    tip_from = math.atan2(flank[0, 1], flank[0, 0])
    tip = prof.tip_radius * np.column_stack(
        [np.cos(b := np.linspace(-tip_from, tip_from, 16)), np.sin(b)])
    outline = np.vstack([negative, tip[1:-1], positive])
    return outline @ rotation(ring.tooth_angle(tooth)).T


def boundary_segments(ring: RingGear, tooth: int, reach: int = 1) -> np.ndarray:
    """Segments (m, 2, 2) [m] of the toothed boundary of teeth ``tooth - reach`` ..
    ``tooth + reach``."""
    parts = [tooth_outline(ring, (tooth + k) % ring.teeth) for k in range(-reach, reach + 1)]
    return np.concatenate([np.stack([p[:-1], p[1:]], axis=1) for p in parts])


def distance_to_segments(point, segments) -> float:
    a, b = segments[:, 0], segments[:, 1]
    d = b - a
    t = np.clip(np.einsum("ij,ij->i", point - a, d) / np.einsum("ij,ij->i", d, d), 0, 1)
    return float(np.min(np.hypot(*(a + t[:, None] * d - point).T)))


@dataclass(frozen=True)
class Exit:
    """Where a ray from inside the ring leaves it.

    Attributes
    ----------
    distance : float
        Along the ray [m].
    point : ndarray
        [m]
    surface : str
        ``"tooth"`` (the toothed inner boundary: the crack would cut the tooth off) or
        ``"rim"`` (the outer surface: it would cut the rim).
    """

    distance: float
    point: np.ndarray
    surface: str


def ray_exit(ring: RingGear, tooth: int, origin, direction) -> Exit:
    """First crossing of the ring's surface by the ray ``origin + s direction``, s > 0."""
    origin = np.asarray(origin, dtype=float)
    d = np.asarray(direction, dtype=float)
    d = d / np.hypot(*d)
    b = float(origin @ d)
    c = float(origin @ origin) - ring.outer_radius ** 2
    outer = -b + math.sqrt(max(b * b - c, 0.0))
    segments = boundary_segments(ring, tooth)
    a, e = segments[:, 0], segments[:, 1] - segments[:, 0]
    cross = d[0] * e[:, 1] - d[1] * e[:, 0]
    ok = np.abs(cross) > 1e-30
    w = a - origin
    s = np.where(ok, (w[:, 0] * e[:, 1] - w[:, 1] * e[:, 0]) / np.where(ok, cross, 1), np.inf)
    t = np.where(ok, (w[:, 0] * d[1] - w[:, 1] * d[0]) / np.where(ok, cross, 1), -1)
    hits = ok & (s > 1e-12) & (t >= 0) & (t <= 1)
    inner = float(s[hits].min()) if np.any(hits) else math.inf
    if inner < outer:
        return Exit(inner, origin + inner * d, "tooth")
    return Exit(outer, origin + outer * d, "rim")


def surface_gap(ring: RingGear, tooth: int, point) -> float:
    """Distance [m] from ``point`` to the nearest surface of the ring (toothed boundary of
    the teeth around ``tooth`` or outer surface)."""
    point = np.asarray(point, dtype=float)
    return min(distance_to_segments(point, boundary_segments(ring, tooth)),
               ring.outer_radius - float(np.hypot(*point)))
