"""Does the crack change the frequencies a running record shows as much as the eigen model's? (SI)

The elastic ring's detection predicts the crack's change of each coupled mode from the
mean-stiffness eigen model (every mesh at its mean stiffness).  A running record shows each
mode as its Floquet mode over the mesh cycle (:mod:`hubvib.signal.elastic_floquet`), whose
frequency differs from the eigen one.  The detection compares a reducer's record with its
own intact record, so what it needs is the crack's *change*: this module puts, per depth
and per intact mode, the eigen change beside the Floquet change, on the same model.

Per depth the elastic case (:func:`hubvib.elastic.cases.cached_case`, faces open) gives the
reduced ring; the time model of the record (:func:`hubvib.signal.elastic_model.elastic_time_model`)
is built from it, and at the diagnosis's carrier position (planet 1 half a planet pitch from
the cracked tooth) the monodromy matrix over one mesh period is formed as
:mod:`hubvib.signal.elastic_floquet` forms it, with the mesh stiffness variation scaled by
``e`` from 0 (the eigen model, whose multipliers are ``exp(s_i T)``) to 1 (the running
reducer) in ``LEVELS`` steps.  Each multiplier is followed along ``e`` (eigenvector overlap
between neighbouring steps, optimal assignment) and its exponent's imaginary part unwrapped
(the branch's ``log`` continued), so every eigen mode ``i`` has one Floquet branch whose
frequency at ``e = 1`` is the *continued Floquet frequency*: ``f_i`` plus the mesh cycle's
drift of that mode.  The record pole of a Floquet mode lies a whole number of mesh
frequencies from it (the harmonic that carries the most amplitude), so the crack's change
of the record frequency equals the change of the continued frequency as long as that
harmonic stays; the record frequency of :func:`hubvib.signal.elastic_floquet.floquet_modes`
(whose attribution may pick another harmonic or leave a mode out) is reported beside it.

The cracked modes are named after the intact modes they continue
(:func:`hubvib.elastic.tracking.track_modes`, match at least
``hubvib.detection.elastic_model.MIN_MATCH``).  The identification scatter and alarm
threshold are the detection's (:meth:`hubvib.detection.options.DetectionOptions.sigma_hz`;
one-sided alarm at ``z sqrt(2) sigma`` with the per-mode rate for the watched modes).

``python -m hubvib.studies.floquet_change --out OUT.json [--depths-mm 0,3,6] [--scene NAME]``
writes the table.
"""
from __future__ import annotations

import argparse
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

#: steps of the mesh-stiffness variation's scale from the eigen model (0) to the record (1)
LEVELS = 24
#: the band of coupled modes tabulated [Hz]
BAND_HZ = (2500.0, 9000.0)
#: largest difference of a branch's frequency followed in ``levels`` and twice as many
#: steps for it to count as unique [Hz]
UNIQUE_HZ = 0.1
#: the default scene's watched elastic modes (1-based), as its report names them
DEFAULT_WATCHED = (16, 21, 22, 24)


@dataclass(frozen=True)
class FloquetBranches:
    """Per kept mode (the time model's order at the position) the Floquet branch that
    continues it: ``frequency_hz`` the continued frequency [Hz] (unwrapped imaginary part of
    the exponent / 2 pi), ``damping_ratio`` [-], ``eigen_hz`` the mean-stiffness frequency
    [Hz], ``mesh_hz`` [Hz], ``levels`` the scale steps followed."""

    frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    eigen_hz: np.ndarray
    mesh_hz: float
    levels: int


@dataclass(frozen=True)
class FloquetChange:
    """The comparison table: per depth (the first 0) and per intact mode of ``modes``
    (0-based, the eigen model's order at the position).

    ``eigen_hz``, ``floquet_hz`` (continued), ``record_hz`` (``floquet_modes``' attributed
    record frequency, NaN where none) (depths, modes) [Hz]; ``sigma_hz`` (modes,) [Hz]
    the identification scatter at ``record_length`` [s]; ``threshold_hz`` the one-sided
    alarm threshold on a change [Hz]; ``watched`` 0-based; ``mesh_hz`` [Hz]."""

    depths_m: tuple
    modes: tuple
    eigen_hz: np.ndarray
    floquet_hz: np.ndarray
    record_hz: np.ndarray
    sigma_hz: np.ndarray
    threshold_hz: np.ndarray
    watched: tuple
    record_length: float
    mesh_hz: float
    position: int
    unique: np.ndarray

    @property
    def eigen_change_hz(self) -> np.ndarray:
        return self.eigen_hz - self.eigen_hz[0]

    @property
    def floquet_change_hz(self) -> np.ndarray:
        return self.floquet_hz - self.floquet_hz[0]

    @property
    def record_change_hz(self) -> np.ndarray:
        return self.record_hz - self.record_hz[0]

    def ratio(self) -> np.ndarray:
        """Floquet change over eigen change (depths, modes) [-] (NaN at depth 0)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.eigen_change_hz != 0,
                            self.floquet_change_hz / self.eigen_change_hz, np.nan)

    def to_dict(self) -> dict:
        def clean(x):
            return None if not np.isfinite(x) else round(float(x), 4)

        ratio = self.ratio()
        rows = []
        for a, i in enumerate(self.modes):
            rows.append({
                "mode": i + 1, "watched": i in self.watched,
                "unique_branch": bool(self.unique[a]),
                "sigma_hz": clean(self.sigma_hz[a]), "threshold_hz": clean(self.threshold_hz[a]),
                "eigen_hz": [clean(x) for x in self.eigen_hz[:, a]],
                "floquet_hz": [clean(x) for x in self.floquet_hz[:, a]],
                "record_hz": [clean(x) for x in self.record_hz[:, a]],
                "eigen_change_hz": [clean(x) for x in self.eigen_change_hz[:, a]],
                "floquet_change_hz": [clean(x) for x in self.floquet_change_hz[:, a]],
                "record_change_hz": [clean(x) for x in self.record_change_hz[:, a]],
                "difference_hz": [clean(x) for x in
                                  self.floquet_change_hz[:, a] - self.eigen_change_hz[:, a]],
                "ratio": [clean(x) for x in ratio[:, a]]})
        return {"depths_mm": [1e3 * d for d in self.depths_m],
                "record_length_s": self.record_length, "mesh_hz": self.mesh_hz,
                "carrier_position": self.position, "modes": rows}


def monodromy(model, curves, phasing, carrier_speed: float, position: int, scale: float,
              steps: int) -> np.ndarray:
    """The monodromy matrix (2 m, 2 m) of the kept modes at ``position`` over one mesh
    period with the mesh stiffness variation scaled by ``scale`` [-] (1: the running
    reducer, as :func:`hubvib.signal.elastic_floquet.floquet_modes`; 0: the eigen model)."""
    from hubvib.signal.elastic_floquet import transition_path

    return transition_path(model, curves, phasing, carrier_speed, position, steps, scale)[2][-1]


def mesh_steps(model, position: int, carrier_speed: float) -> int:
    """Sub-intervals of the mesh period ``floquet_modes`` takes by default."""
    from hubvib.signal.elastic_floquet import default_steps

    return default_steps(model, position, carrier_speed)


def floquet_branches(model, curves, phasing, carrier_speed: float, position: int,
                     levels: int = LEVELS, steps: int | None = None) -> FloquetBranches:
    """Every kept mode's Floquet branch followed from the eigen model to the running
    reducer (module docstring); ``steps`` sub-intervals of the mesh period (None: as
    ``floquet_modes``)."""
    from scipy.optimize import linear_sum_assignment

    from hubvib.foundation.blas import blas_threads

    if levels < 1:
        raise ValueError(f"levels = {levels!r}; allowed: >= 1")
    m = model.kept
    mesh_hz = carrier_speed * model.teeth / (2 * math.pi)
    period = 1.0 / mesh_hz
    if steps is None:
        steps = mesh_steps(model, position, carrier_speed)
    omega = model.omega[position, :m]
    zeta = model.damping_ratio
    # the eigen model's exponents, in the state order (eta, eta') of each mode's eigenvector
    s = -zeta * omega + 1j * omega * math.sqrt(1 - zeta ** 2)
    branch = np.concatenate([s, np.conj(s)])
    # the eigen model's Floquet vectors: mode i's state (e_i, s_i e_i)
    vectors = np.vstack([np.hstack([np.eye(m), np.eye(m)]),
                         np.hstack([np.diag(s), np.diag(np.conj(s))])])
    with blas_threads(1):
        for level in range(1, levels + 1):
            mu, new = np.linalg.eig(monodromy(model, curves, phasing, carrier_speed, position,
                                              level / levels, steps))
            order = _assigned(new, vectors, mu, linear_sum_assignment)
            mu, vectors = mu[order], new[:, order]
            principal = np.log(mu) / period
            turns = np.round((branch.imag - principal.imag) * period / (2 * math.pi))
            branch = principal + 2j * math.pi * turns / period
    top = branch[:m]
    return FloquetBranches(top.imag / (2 * math.pi), -top.real / np.abs(top),
                           omega / (2 * math.pi), mesh_hz, levels)


def _assigned(vectors, previous, mu, assign) -> np.ndarray:
    """Column order of ``vectors`` (eigenvalues ``mu``) that follows ``previous``: the
    assignment of largest total overlap."""
    a = previous / np.linalg.norm(previous, axis=0)
    b = vectors / np.linalg.norm(vectors, axis=0)
    rows, cols = assign(-np.abs(a.conj().T @ b))
    order = np.empty(mu.size, dtype=int)
    order[rows] = cols
    return order


def case_time_model(case, options):
    """The record's time model (``ElasticTimeModel``) of an ``ElasticCase``'s reduced ring
    at the operating point ``options`` (``SignalOptions``)."""
    from hubvib.signal.elastic_model import elastic_time_model
    from hubvib.signal.elastic_record import KEEP_FACTOR

    return elastic_time_model(case.params, case.operators, case.k_rest, options.damping_ratio,
                              options.sun_torque_N_m, KEEP_FACTOR * options.sample_rate_hz / 2)


def floquet_change(scene, depths=(0.0, 0.003, 0.006), watched=DEFAULT_WATCHED,
                   band_hz=BAND_HZ, record_length: float | None = None, curves=None,
                   levels: int = LEVELS, progress=None) -> FloquetChange:
    """The comparison table of ``scene`` (a crack scene with an ``[elastic]`` ring) over
    ``depths`` [m] (the first 0), for the intact modes in ``band_hz`` [Hz] and the
    ``watched`` ones (1-based); ``record_length`` [s] of the scatter (default the
    scene's); ``curves``: the intact mesh curves already scaled (default the FE ones, as
    the records use)."""
    from hubvib.cases.sweep import crack_of
    from hubvib.detection.elastic_model import MIN_MATCH, cached_case, case_arguments
    from hubvib.detection.options import detection_options
    from hubvib.elastic.tracking import track_modes
    from hubvib.signal.elastic_floquet import floquet_modes
    from hubvib.signal.mesh_phase import design_phasing, design_teeth
    from hubvib.signal.simulation import carrier_speed

    if not depths or depths[0] != 0:
        raise ValueError(f"depths = {depths!r}; allowed: the first 0 (the intact ring)")
    sweep, options = scene.crack, scene.signal
    if curves is None:
        from hubvib.cases.sweep import ACCURACY
        from hubvib.signal.mesh_curves import fe_mesh_curves

        fe = fe_mesh_curves((0.0,), sweep.start, sweep.angle, ACCURACY[sweep.accuracy],
                            progress, scene.design)[0]
        curves = fe.to_preset(scene.params.c_sp, scene.params.c_rp)
    teeth = design_teeth(scene.design)
    speed = carrier_speed(options, teeth["ring"], teeth["sun"])
    phasing = design_phasing(scene.design)
    arguments = case_arguments(sweep.reducer, depths, lambda d: crack_of(sweep, d),
                               scene.elastic)
    cases, eigen, continued, coarser, record = [], [], [], [], []
    mesh_hz, position = math.nan, -1
    for depth, a in zip(depths, arguments):
        if progress:
            progress(f"Floquet branches, crack {1e3 * depth:g} mm")
        case = cached_case(*a)
        model = case_time_model(case, options)
        position = case.away.carrier_tooth
        found = floquet_branches(model, curves, phasing, speed, position, levels)
        coarse = floquet_branches(model, curves, phasing, speed, position, 2 * levels)
        shown = floquet_modes(model, curves, phasing, speed, position)
        cases.append(case)
        eigen.append(found.eigen_hz)
        continued.append(found.frequency_hz)
        coarser.append(coarse.frequency_hz)
        record.append(shown.frequency_hz)
        mesh_hz = found.mesh_hz
    intact = cases[0]
    n = min(intact.away.frequency_hz.size, eigen[0].size)
    low, high = band_hz
    watched0 = tuple(int(w) - 1 for w in watched)
    modes = tuple(i for i in range(n) if low <= eigen[0][i] <= high or i in watched0)
    table = {name: np.full((len(depths), len(modes)), np.nan)
             for name in ("eigen", "floquet", "record", "coarse")}
    for k, case in enumerate(cases):
        slot = np.arange(n) if k == 0 else _slots(intact, case, track_modes, MIN_MATCH, n)
        for a, i in enumerate(modes):
            j = slot[i]
            if 0 <= j < eigen[k].size:
                table["eigen"][k, a] = eigen[k][j]
                table["floquet"][k, a] = continued[k][j]
                table["record"][k, a] = record[k][j]
                table["coarse"][k, a] = coarser[k][j]
    detection = detection_options(scene)
    T = detection.record_length if record_length is None else float(record_length)
    sigma = detection.sigma_hz(table["eigen"][0], T)
    from scipy.stats import norm

    z = norm.isf(detection.per_mode_rate(len(watched0)))
    return FloquetChange(tuple(float(d) for d in depths), modes, table["eigen"],
                         table["floquet"], table["record"], sigma, z * math.sqrt(2) * sigma,
                         tuple(w for w in watched0 if w in modes), T, float(mesh_hz),
                         int(position),
                         np.all(np.abs(table["floquet"] - table["coarse"]) <= UNIQUE_HZ, axis=0))


def _slots(intact, case, track_modes, min_match: float, n: int) -> np.ndarray:
    """Per intact mode the index of the cracked mode that continues it (-1: none)."""
    tracked = track_modes(intact.away, case.away, intact.ring_mass)
    slot = np.full(n, -1)
    for j, (ref, match) in enumerate(zip(tracked.reference, tracked.match)):
        if 0 <= ref < n and match >= min_match:
            slot[ref] = j
    return slot


def table_text(result: FloquetChange) -> str:
    """A plain-text rendering of the table (first nonzero depths' changes side by side)."""
    depths = [f"{1e3 * d:g}" for d in result.depths_m[1:]]
    head = ("mode  eigen0_Hz  floquet0_Hz  " + "  ".join(
        f"dEig{d}  dFlq{d}  dRec{d}" for d in depths) + "  sigma  thresh")
    lines = [head]
    for a, i in enumerate(result.modes):
        cells = [f"{i + 1:>3}{'*' if i in result.watched else ' '}"
                 f"{' ' if result.unique[a] else '?'}",
                 f"{result.eigen_hz[0, a]:9.1f}", f"{result.floquet_hz[0, a]:9.1f}"]
        for k in range(1, len(result.depths_m)):
            cells += [f"{result.eigen_change_hz[k, a]:7.2f}",
                      f"{result.floquet_change_hz[k, a]:7.2f}",
                      f"{result.record_change_hz[k, a]:7.2f}"]
        cells += [f"{result.sigma_hz[a]:5.2f}", f"{result.threshold_hz[a]:5.2f}"]
        lines.append("  ".join(cells))
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m hubvib.studies.floquet_change",
        description="The crack's change of the elastic ring's modes: eigen model against "
                    "the Floquet modes a running record shows (JSON table).")
    parser.add_argument("--out", type=Path, required=True, help="JSON file to write")
    parser.add_argument("--scene", default="raba118_crack", help="scene name or TOML path")
    parser.add_argument("--depths-mm", default="0,3,6",
                        help="crack depths [mm], comma-separated, the first 0")
    parser.add_argument("--watched", default=",".join(map(str, DEFAULT_WATCHED)),
                        help="watched modes (1-based), comma-separated")
    args = parser.parse_args(argv)
    from hubvib.studies.scene import load_scene

    try:
        depths = tuple(1e-3 * float(x) for x in args.depths_mm.split(","))
        watched = tuple(int(x) for x in args.watched.split(",") if x.strip())
    except ValueError:
        parser.error("--depths-mm and --watched: comma-separated numbers")
    if not depths or depths[0] != 0 or any(d < 0 for d in depths):
        parser.error("--depths-mm: comma-separated depths >= 0 [mm], the first 0")
    result = floquet_change(load_scene(args.scene), depths, watched)
    args.out.write_text(json.dumps(result.to_dict(), indent=1) + "\n", encoding="utf-8")
    print(table_text(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
