"""The vibration-signature study of a crack scene: per depth, signal, spectrum, indicators.

Per crack depth of the scene's ``[crack]`` table: FE mesh curves (cached), the
periodic steady state of the lumped model over one carrier revolution, the
sensor signal, its band-limited record at the sample rate plus noise (several
seeds), the time-synchronous average and the condition indicators.  The mean
of each indicator over the noise seeds is compared across depths; an indicator
whose mean moves the same way at every step of depth is reported as monotone.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from hubvib.foundation.errors import SceneError
from hubvib.lumped import natural_modes
from hubvib.signal.mesh_curves import fe_mesh_curves
from hubvib.cases.sweep import ACCURACY

from hubvib.signal.ambient import AmbientForcing, ambient_record
from hubvib.signal.contact import force_ratio, mesh_names
from hubvib.signal.manufacturing import load_sharing
from hubvib.signal.frequency_route import frequency_route
from hubvib.signal.indicators import INDICATORS, GearOrders
from hubvib.signal.mesh_curves import MeshCurves
from hubvib.signal.mesh_phase import design_phasing, design_teeth
from hubvib.signal.options import SignalOptions
from hubvib.signal.records import indicator_run, summarise
from hubvib.signal.roc import detection_rates
from hubvib.signal.accelerometer import sampled, sensor_signal
from hubvib.signal.sensor_array import sensor_rows
from hubvib.signal.simulation import Simulation, carrier_speed, simulate, steps_per_revolution
from hubvib.signal.speed import SpeedProfile, angle_from_tacho
from hubvib.signal.spectral import (HarmonicRule, OrderSpectrum, PlanetErrorRule, SidebandRule,
                       non_multiple_fraction, order_spectrum, top_harmonics)

#: labelled lines listed per depth
TOP_LINES = 12
#: planet-pass sidebands on either side of the last analysed mesh harmonic in the
#: step-halving check
SER_REACH = 6


@dataclass
class DepthSignal:
    """One crack depth.

    Attributes
    ----------
    depth : float
        [m]
    revolution : ndarray
        Noise-free sensor signal over one carrier revolution on the step grid [m/s^2].
    spectrum : OrderSpectrum
        c_k, phi_k of ``revolution`` up to the Nyquist order of the sample rate.
    time, record : ndarray
        Sampled record with the noise of the first seed [s, m/s^2].
    tsa : list of ndarray
        Time-synchronous average of each seed's record [m/s^2].
    values : list of Indicators
        Per seed.
    lines : list of LabelledHarmonic
        The largest lines of ``spectrum`` with their labels.
    seconds : float
        Wall time of the simulation [s].
    non_multiple_fraction : float
        Energy share of the carrier orders that are not multiples of N [-].
    contact : dict
        Per mesh: smallest total/static force of the linear model and the fraction of
        the revolution spent separated in the piecewise model [-].
    """

    depth: float
    revolution: np.ndarray
    spectrum: OrderSpectrum
    time: np.ndarray
    record: np.ndarray
    tsa: list = field(default_factory=list)
    values: list = field(default_factory=list)
    lines: list = field(default_factory=list)
    seconds: float = 0.0
    non_multiple_fraction: float = 0.0
    contact: dict = field(default_factory=dict)

    def summary(self) -> dict:
        """Mean and standard deviation of each indicator over the seeds."""
        return summarise(self.values, INDICATORS)


@dataclass
class SignalStudy:
    """The whole study (SI): the options, the kinematics and every depth."""

    scene_name: str
    options: SignalOptions
    carrier_hz: float
    mesh_hz: float
    n_planets: int
    step: float
    steps_per_revolution: int
    points_per_revolution: int
    noise_rms: float
    depths: list[DepthSignal]
    checks: dict = field(default_factory=dict)
    crack_tooth: int = 0

    ring_teeth: int = 64
    load_sharing: list = field(default_factory=list)
    sensors: list = field(default_factory=list)
    roc: dict | None = None
    tacho: np.ndarray | None = None

    @property
    def gear(self) -> GearOrders:
        return GearOrders(self.ring_teeth, self.n_planets, self.options.mesh_harmonics,
                          self.options.indicator_max_order)

    def monotone(self) -> list[dict]:
        """Indicators whose seed-mean moves the same way at every depth step."""
        out = []
        for name in INDICATORS:
            means = np.array([d.summary()[name]["mean"] for d in self.depths])
            steps = np.diff(means)
            if steps.size and (np.all(steps > 0) or np.all(steps < 0)):
                intact = self.depths[0].summary()[name]
                spread = intact["std"] or math.inf
                out.append({"indicator": name,
                            "direction": "increasing" if steps[0] > 0 else "decreasing",
                            "separation_at_deepest": float((means[-1] - means[0]) / spread)})
        return out


def harmonic_rules(n_planets: int, design, errors: bool = False) -> list[HarmonicRule]:
    """Labels of carrier orders: mesh harmonics, planet-pass / cracked-tooth sidebands
    (multiples of N around them), planet-pass orders, shaft orders, and with ``errors``
    the other integer orders (planet errors, load sharing); else unexplained."""
    teeth = design_teeth(design)
    z_r, z_s, z_p = teeth["ring"], teeth["sun"], teeth["planet"]
    extra = [PlanetErrorRule(z_r, n_planets)] if errors else []
    return [
        HarmonicRule("z_r", z_r, meaning="ring mesh harmonic"),
        SidebandRule("z_r", z_r, n_planets, "N",
                     meaning="planet-pass / cracked-tooth sideband of a mesh harmonic"),
        HarmonicRule("N", n_planets, meaning="planet-pass order"),
        HarmonicRule("carrier", 1, 2, meaning="carrier shaft order"),
        HarmonicRule("sun", (z_s + z_r) / z_s, 3, meaning="sun shaft order (relative)"),
        HarmonicRule("planet", abs(1 - z_r / z_p), 3, meaning="planet spin order"),
    ] + extra + extra


def curves_for(scene, options: SignalOptions, progress=None) -> list[MeshCurves]:
    """The mesh curves of every depth, scaled as ``options.mesh_stiffness`` says."""
    sweep = scene.crack
    depths = sweep.depths if sweep is not None else (0.0,)
    fe = fe_mesh_curves(depths, sweep.start if sweep else "root",
                        sweep.angle if sweep else 0.0,
                        ACCURACY[sweep.accuracy] if sweep else 1.0, progress, scene.design)
    if options.mesh_stiffness == "ratio":
        return [c.to_preset(scene.params.c_sp, scene.params.c_rp) for c in fe]
    return fe


def check_crack_model(scene) -> None:
    """``SceneError`` for a scene whose cracks the signal study cannot model: its mesh
    curves come from the plane FE tooth (a crack through the whole face width), so the
    solid model's semi-elliptic part-width cracks would be simulated as through-width
    cracks (``hubvib signal raba118_crack_3d`` did so and exited 0)."""
    sweep = scene.crack
    if sweep is not None and sweep.model != "plane":
        raise SceneError(
            f"scene {scene.name!r}: [crack] model = {sweep.model!r} gives semi-elliptic "
            f"part-width cracks (half_lengths {', '.join(f'{1e3 * c:g}' for c in sweep.half_lengths)}"
            f" mm), but the signal study's mesh stiffness comes from the plane FE tooth, a "
            f"crack through the whole face width; allowed for a signal study: [crack] "
            f"model = \"plane\" (e.g. the scene raba118_signal)")
    if sweep is not None and sweep.path != "straight":
        raise SceneError(
            f"scene {scene.name!r}: [crack] path = {sweep.path!r}, but the signal study's "
            "mesh curves come from straight cracks; allowed for a signal study: [crack] "
            "path = \"radial\" or an angle [deg]")


def run_signal_study(scene, curves: list[MeshCurves] | None = None,
                     options: SignalOptions | None = None, progress=None) -> SignalStudy:
    """Run the study of ``scene`` (its ``[signal]`` and ``[crack]`` tables).

    ``curves`` (one per depth, already scaled) replace the FE curves, e.g. in tests.
    Nothing is written here; every input error is raised before any output exists.
    """
    check_crack_model(scene)
    options = options or scene.signal
    params = scene.params
    teeth = design_teeth(scene.design)
    if options.mesh_stiffness == "ratio":  # the mean system is known: check h before any FE
        omega = natural_modes(params.replace(c_rp_factors=())).omega.max()
        speed = carrier_speed(options, teeth["ring"], teeth["sun"])
        steps_per_revolution(float(omega), speed, teeth["ring"], options, params.n_planets)
    if curves is None:
        curves = curves_for(scene, options, progress)
    phasing = design_phasing(scene.design)
    tooth = scene.crack.tooth if scene.crack is not None else 0
    gear = GearOrders(teeth["ring"], params.n_planets, options.mesh_harmonics,
                      options.indicator_max_order)
    try:
        options.errors.per_planet(params.n_planets)
    except ValueError as exc:
        raise SceneError(str(exc)) from None
    if options.roc_records and options.noise_level == 0:
        raise SceneError("[signal] noise_level = 0 with roc_records > 0: every record is the "
                         "same, no detection rate; allowed: noise_level > 0 or roc_records = 0")
    depth_list = scene.crack.depths if scene.crack is not None else (0.0,)
    if options.roc_records and depth_list[0] != 0.0:
        raise SceneError(f"[crack] depths = {list(depth_list)}: detection rates need the "
                         f"intact case 0.0 first; allowed: depths starting at 0.0, or "
                         f"[signal] roc_records = 0")
    rules = harmonic_rules(params.n_planets, scene.design, options.errors.any())
    depths, sims = [], []
    for c in curves:
        started = time.perf_counter()
        sim = simulate(params, c, phasing, options, tooth, 1, teeth["sun"])
        sims.append(sim)
        revolution = sensor_signal(sim, options.sensor_angle, options.rigid_path)[:-1]
        spectrum = _below_nyquist(order_spectrum(revolution), sim, options)
        depths.append(DepthSignal(c.depth, revolution, spectrum, np.empty(0), np.empty(0),
                                  lines=top_harmonics(spectrum, rules, TOP_LINES),
                                  seconds=time.perf_counter() - started,
                                  non_multiple_fraction=non_multiple_fraction(
                                      spectrum, params.n_planets),
                                  contact=contact_summary(sim)))
    carrier_hz = sims[0].carrier_speed / (2 * math.pi)
    duration = options.revolutions / carrier_hz
    speed = SpeedProfile(carrier_hz, options.speed_fluctuation, options.speed_fluctuation_hz)
    varying = speed if options.speed_fluctuation else None
    clean = [sampled(d.revolution, carrier_hz, options.sample_rate_hz, duration, varying)
             for d in depths]
    pulses = speed.pulses(clean[0][0][-1], options.tacho_pulses_per_revolution)
    angle = angle_from_tacho(pulses, clean[0][0], options.tacho_pulses_per_revolution) \
        if varying else \
        2 * math.pi * carrier_hz * clean[0][0]
    noise_rms = options.noise_level * float(np.sqrt(np.mean(clean[0][1] ** 2)))
    points = 2 ** int(math.ceil(math.log2(options.sample_rate_hz / carrier_hz)))
    first, tsas, values = indicator_run(clean, angle, points, gear, noise_rms,
                                        range(options.noise_seeds))
    for d, (t, _), record, tsa, v in zip(depths, clean, first, tsas, values):
        d.time, d.record, d.tsa, d.values = t, record, tsa, v
    if options.ambient_force_psd_N2_Hz > 0:
        true_angle = varying.angle(clean[0][0]) if varying else angle
        forcing = AmbientForcing(options.ambient_force_psd_N2_Hz)
        for k, (d, sim, c) in enumerate(zip(depths, sims, curves)):
            rng = np.random.default_rng([options.ambient_seed, k])
            d.record = d.record + ambient_record(sim.dynamics, c, phasing, forcing, true_angle,
                                                 options.sample_rate_hz, options.sensor_angle,
                                                 tooth, rng)
    study = SignalStudy(scene.name, options, carrier_hz, carrier_hz * teeth["ring"],
                        params.n_planets, sims[0].step, sims[0].steps_per_revolution, points,
                        noise_rms, depths, crack_tooth=tooth, ring_teeth=teeth["ring"])
    study.checks = _checks(study, params, curves[0], phasing, options, teeth["sun"])
    study.load_sharing = [float(v) for v in load_sharing(sims[0].dynamics.static_force,
                                                          params.n_planets)]
    study.tacho = pulses
    if options.roc_records:
        study.roc = detection_rates([d.depth for d in depths], clean, angle, points, gear,
                                    noise_rms, options.roc_records, options.false_alarm_rate)
        study.roc["frequency_route"] = frequency_route(
            params, curves, phasing, options.damping_ratio, duration, options.sample_rate_hz,
            options.false_alarm_rate)
    study.sensors = [sensor_rows(sims, [d.depth for d in depths], offset, tooth, gear, options,
                                 (varying, angle), points, noise_rms)
                     for offset in options.sensor_angles_from_crack_deg]
    return study


def contact_summary(sim: Simulation) -> dict:
    """Per mesh: the smallest total/static force ratio of the linear model and the fraction
    of the revolution separated in the piecewise contact model [-]."""
    names = mesh_names(sim.dynamics.n_planets)
    return {"min_force_ratio": dict(zip(names, map(float, sim.linear_min_force_ratio))),
            "separated_fraction": dict(zip(names, map(float, sim.separated))),
            "min_force_ratio_after": dict(zip(names, map(float, force_ratio(
                sim.dynamics, sim.forces).min(axis=0))))}


def _below_nyquist(spectrum: OrderSpectrum, sim: Simulation,
                   options: SignalOptions) -> OrderSpectrum:
    carrier_hz = sim.carrier_speed / (2 * math.pi)
    top = int(math.ceil(options.sample_rate_hz / 2 / carrier_hz)) - 1
    top = min(top, spectrum.nyquist_order)
    return OrderSpectrum(spectrum.orders[:top + 1], spectrum.amplitude[:top + 1],
                         spectrum.phase[:top + 1])


def step_halving_change(params, curves: MeshCurves, phasing, options: SignalOptions,
                        max_order: int, full_order: int | None, sun_teeth: int) -> dict:
    """Largest change of the order amplitudes when the time step is halved, relative to the
    largest amplitude [-]: orders <= ``max_order`` (the analysed band) and, with
    ``full_order``, orders <= ``full_order`` (up to the Nyquist order of the record)."""
    spectra = []
    for factor in (1, 2):
        halved = replace(options, steps_per_period=options.steps_per_period * factor,
                         time_step_s=options.time_step_s / factor)
        sim = simulate(params, curves, phasing, halved, None, 1, sun_teeth)
        spectra.append(order_spectrum(sensor_signal(sim, options.sensor_angle,
                                                    options.rigid_path)[:-1]))

    def change(top):
        a, b = (s.amplitude[1:top + 1] for s in spectra)
        return float(np.max(np.abs(a - b)) / a.max())

    out = {"max_order": max_order, "relative_change": change(max_order)}
    if full_order is not None:
        out |= {"full_order": full_order, "full_band_relative_change": change(full_order)}
    return out


def _checks(study: SignalStudy, params, intact: MeshCurves, phasing, options, sun_teeth: int) -> dict:
    """Cancellation rule on the intact spectrum and the step-halving change."""
    spectrum = study.depths[0].spectrum
    n = study.n_planets
    amplitude = spectrum.amplitude[1:]
    orders = spectrum.orders[1:]
    off = orders % n != 0
    top = options.mesh_harmonics * study.ring_teeth + SER_REACH * n
    out = {"non_multiple_of_N_relative": float(amplitude[off].max() / amplitude.max())
           if off.any() else 0.0}
    if params.equally_spaced() and params.n_planets == 3 and params.c_s == 0:
        out["load_sharing_rule"] = (
            "floating sun, three planets: the sun's force balance leaves only equal mesh "
            "forces, whatever the pin-hole errors (Kahraman 1994)")
    if params.equally_spaced() and not options.errors.any():
        out["cancellation_rule"] = (
            "equally spaced planets: only carrier orders that are multiples of N reach a "
            "sensor fixed on the ring (McFadden & Smith 1985; Parker & Lin 2004)")
    out["step_halving"] = step_halving_change(params, intact, phasing, options, top,
                                              spectrum.nyquist_order, sun_teeth)
    return out

