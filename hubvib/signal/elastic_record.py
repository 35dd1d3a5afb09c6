"""Records of a crack scene on the elastic ring: one accelerometer record per crack depth (SI).

Per depth of the scene's ``[crack]`` table the design's FE ring (faces open) is reduced
with the contact responses of every ring tooth (the carrier takes each planet past all of
them), coupled to the lumped bodies and integrated in time
(:mod:`hubvib.signal.elastic_response`) at the scene's ``[signal]`` operating point: the
intact FE mesh curves (the crack is in the ring body, not in the mesh curve), its
transmission error, white ambient forces of ``ambient_force_psd_N2_Hz`` seeded by
``ambient_seed`` and the depth, and the sensor's radial acceleration on the mid-rim circle at
``[elastic] sensor_angle_deg`` from the cracked tooth, plus white measurement noise of
``noise_level`` times the intact record's RMS.  The record lasts ``revolutions`` carrier
revolutions, so the mesh and planet-pass lines fall on frequency lines.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .elastic_model import elastic_time_model
from .elastic_response import Operation, elastic_record
from .mesh_phase import design_phasing, design_teeth
from .options import SignalOptions
from .simulation import carrier_speed

#: modes integrated in time up to this multiple of the record's Nyquist frequency (the
#: higher ones respond quasi-statically)
KEEP_FACTOR = 1.5
#: integrator steps per sample
SUBSTEPS = 2


@dataclass(frozen=True)
class DepthRecord:
    """One depth's record: ``values`` [m/s^2] at ``sample_rate`` [Hz]; ``seconds`` the
    wall time of the model and the integration, ``integration_seconds`` of the time
    integration alone, over ``steps`` steps of ``modes`` modes."""

    depth: float
    values: np.ndarray
    sample_rate: float
    seconds: float
    steps: int
    integration_seconds: float
    modes: int

    @property
    def time(self) -> np.ndarray:
        return np.arange(self.values.size) / self.sample_rate


def elastic_ring_all_teeth(design, crack, scene_elastic, k_rest: float):
    """The design's elastic ring (faces open) with the contact responses of every tooth."""
    from hubvib.elastic.model import elastic_ring
    from hubvib.reducer.stages import ring_gear

    teeth = tuple(range(ring_gear(design).teeth))
    return elastic_ring(design, crack, False, scene_elastic.options, teeth, k_rest=k_rest)


def sensor_polar_angle(ring_operators, crack_tooth: int, sensor_angle: float) -> float:
    """The sensor's polar angle [rad]: the cracked tooth's centre line (``2 pi k / z``) plus
    ``sensor_angle`` (``[elastic] sensor_angle_deg``)."""
    return 2 * math.pi * crack_tooth / ring_operators.teeth + sensor_angle


def depth_record(design, er, curves, options: SignalOptions, sensor_angle: float,
                 crack_tooth: int, seed, noise_rms: float | None = None,
                 substeps: int = SUBSTEPS, ring_stiffness=None) -> tuple[DepthRecord, float]:
    """The record of one elastic ring ``er`` (``hubvib.elastic.model.ElasticRing``);
    returns it and the noise RMS used (``noise_rms`` None: ``noise_level`` times this
    record's own RMS)."""
    started = time.perf_counter()
    teeth = design_teeth(design)
    model = elastic_time_model(er.params, er.operators, er.k_rest, options.damping_ratio,
                               options.sun_torque_N_m, KEEP_FACTOR * options.sample_rate_hz / 2,
                               ring_stiffness)
    speed = carrier_speed(options, teeth["ring"], teeth["sun"])
    duration = options.revolutions * 2 * math.pi / speed
    operation = Operation(speed, options.sample_rate_hz, duration, substeps,
                          options.transmission_error_m, options.ambient_force_psd_N2_Hz)
    rng = np.random.default_rng(seed)
    angle = sensor_polar_angle(er.operators, crack_tooth, sensor_angle)
    rec = elastic_record(model, curves, design_phasing(design), operation, angle, rng)
    values = rec.values
    if noise_rms is None:
        noise_rms = options.noise_level * float(np.sqrt(np.mean(values ** 2)))
    if noise_rms > 0:
        values = values + noise_rms * rng.standard_normal(values.size)
    return DepthRecord(0.0 if er.crack is None else float(er.crack.depth), values,
                       options.sample_rate_hz, time.perf_counter() - started, rec.steps,
                       rec.seconds, model.modes), noise_rms


def scene_records(scene, progress=None, curves=None) -> list[DepthRecord]:
    """One record per depth of ``scene`` (``[crack]``, ``[signal]``, ``[elastic]``), the
    intact first; ``curves``: the intact mesh curves already scaled (else the FE ones)."""
    from hubvib.elastic.rest import rest_stiffness

    options = scene.signal
    elastic = scene.elastic
    sweep = scene.crack
    if sweep is None:
        raise ValueError("an elastic-ring record needs a [crack] table (its tooth, depths)")
    if curves is None:
        from hubvib.cases.sweep import ACCURACY
        from .mesh_curves import fe_mesh_curves

        fe = fe_mesh_curves((0.0,), sweep.start, sweep.angle, ACCURACY[sweep.accuracy],
                            progress, scene.design)[0]
        curves = fe.to_preset(scene.params.c_sp, scene.params.c_rp)
    from hubvib.cases.sweep import crack_of

    k_rest = rest_stiffness(scene.design, elastic.options.rest)
    out, noise = [], None
    for k, depth in enumerate(sweep.depths):
        if progress:
            progress(f"elastic ring record, crack {1e3 * depth:g} mm")
        er = elastic_ring_all_teeth(scene.design, crack_of(sweep, depth) if depth > 0 else None,
                                    elastic, k_rest)
        rec, noise = depth_record(scene.design, er, curves, options, elastic.sensor_angle,
                                  sweep.tooth, [options.ambient_seed, k], noise)
        out.append(rec)
    return out



def scene_floquet_shift(scene, curves=None, progress=None) -> np.ndarray:
    """Per coupled mode of the intact elastic ring (the eigen model's order with planet 1
    half a planet pitch from the cracked tooth, the diagnosis's position), how far the
    mesh cycle moves the frequency a record of the scene shows [Hz]: the Floquet mode's
    frequency less the mean-stiffness one (:mod:`.elastic_floquet`; NaN where no Floquet
    mode is attributed); ``curves``: the intact mesh curves already scaled (else the FE
    ones, as :func:`scene_records`)."""
    from hubvib.elastic.cases import carrier_positions
    from hubvib.elastic.rest import rest_stiffness

    from .elastic_floquet import floquet_modes
    from .mesh_phase import design_phasing

    options, elastic, sweep = scene.signal, scene.elastic, scene.crack
    if sweep is None:
        raise ValueError("the elastic ring's record frequencies need a [crack] table (its "
                         "tooth)")
    if curves is None:
        from hubvib.cases.sweep import ACCURACY
        from .mesh_curves import fe_mesh_curves

        fe = fe_mesh_curves((0.0,), sweep.start, sweep.angle, ACCURACY[sweep.accuracy],
                            progress, scene.design)[0]
        curves = fe.to_preset(scene.params.c_sp, scene.params.c_rp)
    er = elastic_ring_all_teeth(scene.design, None, elastic,
                                rest_stiffness(scene.design, elastic.options.rest))
    teeth = design_teeth(scene.design)
    model = elastic_time_model(er.params, er.operators, er.k_rest, options.damping_ratio,
                               options.sun_torque_N_m, KEEP_FACTOR * options.sample_rate_hz / 2)
    away, _ = carrier_positions(scene.design, sweep.tooth)
    found = floquet_modes(model, curves, design_phasing(scene.design),
                          carrier_speed(options, teeth["ring"], teeth["sun"]), away)
    return found.frequency_hz - found.mean_hz
