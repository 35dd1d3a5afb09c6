"""The plane ring as pieces that glue at their cuts: the block around the crack, the
pitches that hold a support end, and copies of one plain pitch (SI units).

Every piece is a ``ring_block.block_mesh``, so all cuts carry the same nodes and the
pieces glue into one conforming ring mesh (``RingPieces.mesh``): the whole ring
assembled from the pieces, its groups as ``ring_mesh``'s.  The block spans the pitches
within ``MARGIN`` pitches of the crack (its mouth when intact); a pitch with a support
end on its arc or cuts is meshed in place with that end as a node; every other pitch is
the plain pitch of tooth 0 (no support end) turned to its place.  Only the block depends
on the crack: the other pieces are the same for every crack case of a ring and options.
"""
from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass, replace

import numpy as np

from .crack import Crack
from .fe_mesh import FEMesh
from .gear import rotation
from .ring_block import block_mesh, ends_in
from .ring_gear import RingGear
from .ring_mesh import MeshOptions
from .session import MeshingError

#: the crack block reaches this many pitches beyond the crack on either side [-]
MARGIN = 1.0


@dataclass(frozen=True, eq=False)
class Piece:
    """One piece of the ring.

    Attributes
    ----------
    mesh : FEMesh
        The piece in its own frame (``block_mesh``).
    first, count : int
        Its first tooth and number of pitches, where it sits in the ring.
    angle : float
        Rotation from the mesh's frame to its place [rad] (0 for pieces meshed in place).
    kind : str
        ``"block"`` (the crack's), ``"support"`` (a support end inside) or ``"plain"``.
    nodes : ndarray
        Index in the ring mesh of each node of ``mesh``.
    held : ndarray of bool
        For each facet of the mesh's ``outer`` group, whether it lies in a support arc.
    """

    mesh: FEMesh
    first: int
    count: int
    angle: float
    kind: str
    nodes: np.ndarray
    held: np.ndarray

    @property
    def cut_nodes(self) -> np.ndarray:
        """Nodes of both cuts (mesh indices)."""
        return np.unique(np.concatenate([self.mesh.boundaries["cut_minus"].ravel(),
                                         self.mesh.boundaries["cut_plus"].ravel()]))

    @property
    def held_nodes(self) -> np.ndarray:
        """Nodes of held outer facets that are on no cut (mesh indices)."""
        held = np.unique(self.mesh.boundaries["outer"][self.held].ravel())
        return np.setdiff1d(held, self.cut_nodes)


@dataclass(frozen=True, eq=False)
class RingPieces:
    """The ring's pieces and the ring mesh they glue into (``mesh``; every piece's
    ``nodes`` index it)."""

    mesh: FEMesh
    pieces: tuple

    @property
    def block(self) -> Piece:
        return next(p for p in self.pieces if p.kind == "block")


def block_teeth(ring: RingGear, crack) -> tuple[int, int]:
    """First tooth and pitch count of the crack's block: the pitches within ``MARGIN``
    of the crack's path (of its mouth for ``None`` or depth 0, tooth 0 for ``None``)."""
    z = ring.teeth
    crack = Crack(0) if crack is None else crack
    if crack.depth > 0:
        path = crack.path(ring) if isinstance(crack, Crack) else np.asarray(crack.array)
    else:
        path = Crack(crack.tooth, 0.0, getattr(crack, "angle", 0.0),
                     crack.start).mouth(ring)[None, :]
    pitch = 2 * math.pi / z
    centre = ring.tooth_angle(crack.tooth)
    offsets = (np.arctan2(path[:, 1], path[:, 0]) - centre + math.pi) % (2 * math.pi) - math.pi
    low = math.floor(offsets.min() / pitch - MARGIN + 0.5)
    high = math.ceil(offsets.max() / pitch + MARGIN - 0.5)
    count = high - low + 1
    if count >= z:
        raise MeshingError(f"the crack's block would span {count} of the ring's {z} pitches")
    return (crack.tooth + low) % z, count


#: where intact pieces' meshes come from beside this process's memory (``set_mesh_store``)
_STORE = None


def set_mesh_store(store) -> None:
    """Let ``store(compute, inputs)`` give the intact pieces' meshes (None: mesh them
    here): it returns the ``FEMesh`` that ``compute()`` returns for ``inputs`` (ring,
    first tooth, pitch count, options, plain), e.g. from a result cache on disk."""
    global _STORE
    _STORE = store


@functools.lru_cache(maxsize=64)
def piece_mesh(ring: RingGear, first: int, count: int, options: MeshOptions,
               plain: bool = False) -> FEMesh:
    """An intact piece's mesh, kept between calls: the plain pitch of tooth 0 (no support
    end) with ``plain``, else the pitches in place with their support ends."""
    def compute() -> FEMesh:
        return block_mesh(ring, first, count, options, None, () if plain else None)
    return compute() if _STORE is None else _STORE(compute, (ring, first, count, options,
                                                             plain))


def ring_pieces(ring: RingGear, crack=None, options: MeshOptions = MeshOptions()
                ) -> RingPieces:
    """The ring with ``crack`` (None or depth 0: intact) as glued pieces."""
    started = time.perf_counter()
    z = ring.teeth
    first, count = block_teeth(ring, crack)
    placed = [(first, count, 0.0, "block", block_mesh(ring, first, count, options, crack))]
    meshed = time.perf_counter() - started
    for j in range(count, z):
        k = (first + j) % z
        if len(ends_in(ring, k, 1)):
            placed.append((k, 1, 0.0, "support", piece_mesh(ring, k, 1, options)))
        else:
            placed.append((k, 1, ring.tooth_angle(k), "plain",
                           piece_mesh(ring, 0, 1, options, plain=True)))
    return glue(ring, placed, meshed)


def _cut(mesh: FEMesh, name: str) -> np.ndarray:
    """Nodes of a cut ordered by radius."""
    nodes = np.unique(mesh.boundaries[name])
    return nodes[np.argsort(np.hypot(*mesh.points[nodes].T))]


def glue(ring: RingGear, placed: list, seconds_block: float = 0.0) -> RingPieces:
    """Glue ``placed`` pieces ``(first, count, angle, kind, mesh)``, consecutive around
    the ring, at their cuts into one ring mesh (groups as ``ring_mesh``)."""
    from .ring_sector import in_support

    tol = 1e-9 * ring.held_radius
    points, cells, quality = [], [], []
    groups: dict = {}
    pieces = []
    total = 0
    first_minus = previous_plus = None
    for index, (first, count, angle, kind, mesh) in enumerate(placed):
        turned = mesh.points @ rotation(angle).T
        nodes = np.full(len(mesh.points), -1, dtype=np.int64)
        minus, plus = _cut(mesh, "cut_minus"), _cut(mesh, "cut_plus")
        shared = [(minus, previous_plus)] if index else []
        if index == len(placed) - 1:
            shared.append((plus, first_minus))
        for own, other in shared:
            if len(own) != len(other[0]) or np.abs(turned[own] - other[1]).max() > tol:
                raise MeshingError(f"piece at tooth {first}: its cut does not match its "
                                   f"neighbour's ({len(own)} and {len(other[0])} nodes)")
            nodes[own] = other[0]
        new = nodes < 0
        nodes[new] = total + np.arange(new.sum())
        total += int(new.sum())
        points.append(turned[new])
        cells.append(nodes[mesh.cells])
        if mesh.cell_quality is not None:
            quality.append(mesh.cell_quality)
        if index == 0:
            first_minus = (nodes[minus], turned[minus])
        previous_plus = (nodes[plus], turned[plus])
        outer = mesh.boundaries["outer"]
        middle = (turned[outer[:, 2]] if outer.shape[1] == 3
                  else turned[outer[:, :2]].mean(axis=1))
        held = (in_support(ring, np.arctan2(middle[:, 1], middle[:, 0]))
                if ring.supports.count else np.ones(len(outer), dtype=bool))
        groups.setdefault("supports", []).append(nodes[outer[held]])
        groups.setdefault("outer_free", []).append(nodes[outer[~held]])
        for name, facets in mesh.boundaries.items():
            if name in ("cut_minus", "cut_plus", "outer"):
                continue
            if kind == "plain":
                name = name.replace("tooth0_", f"tooth{first}_")
            groups.setdefault(name, []).append(nodes[facets])
        pieces.append(Piece(mesh, first, count, angle, kind, nodes, held))
    groups = {k: np.vstack(v) for k, v in groups.items()}
    block = pieces[0].mesh
    points_of = {k: pieces[0].nodes[v] for k, v in block.points_of.items()}
    info = dict(block.info, nodes=total, elements=int(sum(len(c) for c in cells)),
                seconds=seconds_block, pieces=len(pieces))
    mesh = FEMesh(np.vstack(points), np.vstack(cells), block.cell_type, groups, points_of, info,
                  np.concatenate(quality) if len(quality) == len(pieces) else None)
    if len(np.unique(mesh.cells)) != total:
        raise MeshingError("the glued ring has nodes no cell uses")
    return RingPieces(replace(mesh), tuple(pieces))
