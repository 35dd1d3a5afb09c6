"""The crack sweep: which cracks an FE crack-case stage analyses and how (SI).

``CrackSweep`` lists the crack depths (and, in the solid model, the half-lengths), the
tooth, where the crack starts and runs, the accuracy preset and how the FE values enter
the lumped model; ``crack_of`` gives the crack of one depth (straight, or along the
predicted LEFM path, ``hubvib.cases.predicted_path``).
"""
from __future__ import annotations

from dataclasses import dataclass

from hubvib.cases.predicted_path import predicted_crack
from hubvib.meshing.crack import Crack, CrackFront

APPLY = ("series", "ratio", "direct")
MODELS = ("plane", "solid")
#: how the crack runs: straight at ``angle`` ("radial" in a scene: angle 0) or along the
#: LEFM path of ``hubvib crack-path`` (``hubvib.cases.predicted_path``)
PATHS = ("straight", "predicted")
#: mesh size multiplier of each accuracy setting (1.0: c_ru to ~0.3 %, see README)
ACCURACY = {"default": 1.0, "fast": 2.0}
#: at most this many depths in one sweep
MAX_DEPTHS = 64


@dataclass(frozen=True)
class CrackSweep:
    """Crack depths to analyse in the ring gear of the reducer.

    Parameters
    ----------
    depths : tuple of float
        Crack depths [m] along the path, ascending, starting at 0 (the intact ring).
    tooth, start, angle
        Tooth index, ``"root"`` or ``"rim"``, direction from the radial [rad].
    apply : str
        How FE enters the lumped model: ``"series"`` puts the ring mounting in series
        with the FE ring body, ``1/c = 1/c_mount + 1/c_body(depth)``; ``"ratio"`` scales
        the preset's ``c_ru`` and ``c_r`` by FE(depth) / FE(0) (the paper's hypothesis:
        the whole compliance is the ring body, an upper bound of the effect);
        ``"direct"`` uses the FE values themselves (a rigid mounting).
    accuracy : str
        ``"default"`` or ``"fast"`` (element sizes doubled).
    workers : int
        Worker processes for the FE cases (1 = in this process).
    c_ru_mount, c_r_mount : float or None
        With ``"series"``: the mounting's torsional and radial stiffness [N/m]; ``None``
        identifies it so that the intact total equals the preset's ``c_ru`` / ``c_r``.
    design : ReducerDesign or None
        The reducer whose ring is cracked; ``None`` = Raba 118/76.
    model : str
        ``"plane"`` (cracks through the face width, plane stress) or ``"solid"``
        (semi-elliptic root cracks in the solid ring, one per depth and half-length).
    half_lengths : tuple of float
        With ``"solid"``: half the crack mouth's length along the face width [m].
    path : str
        ``"straight"`` (the crack runs straight at ``angle``) or ``"predicted"`` (along
        the LEFM path of ``hubvib crack-path`` at ``tooth``, ``depths`` are arc lengths
        along it; root cracks in the plane model only).
    """

    depths: tuple[float, ...]
    tooth: int = 0
    start: str = "root"
    angle: float = 0.0
    apply: str = "series"
    accuracy: str = "default"
    workers: int = 2
    c_ru_mount: float | None = None
    c_r_mount: float | None = None
    design: object = None
    model: str = "plane"
    half_lengths: tuple[float, ...] = ()
    path: str = "straight"
    substructure: bool = True

    @property
    def cases(self) -> list:
        """The FE cases: depths [m] in the plane; ``(depth, half_length)`` [m] in the solid,
        the intact ring first as ``(0.0, 0.0)``."""
        if self.model == "plane":
            return list(self.depths)
        return [(0.0, 0.0)] + [(d, c) for c in self.half_lengths for d in self.depths if d > 0]

    @property
    def reducer(self):
        """The design whose ring is cracked (``design``; no default reducer)."""
        if self.design is None:
            raise ValueError("CrackSweep.design is None; give the reducer design "
                             "(e.g. hubvib.design.preset_design(\"raba118\"))")
        return self.design


def crack_of(sweep: CrackSweep, depth: float):
    """The crack of ``sweep`` at ``depth`` [m]: a ``Crack`` straight at ``sweep.angle``,
    or with ``path = "predicted"`` the predicted path up to arc length ``depth`` (a
    ``PathCrack``; the intact ring, depth 0, stays a ``Crack``)."""
    if sweep.path == "predicted" and depth > 0:
        return predicted_crack(sweep.reducer, sweep.tooth, sweep.depths, float(depth))
    return Crack(sweep.tooth, float(depth), sweep.angle, sweep.start)


def front_of(half_length: float):
    """The semi-elliptic front of a solid case, centred on the face width."""
    return CrackFront("semi_elliptic", 0.5, float(half_length))
