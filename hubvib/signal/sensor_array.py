"""Several sensors on the ring, placed relative to the cracked tooth.

The study's own sensor sits at ``sensor_angle_deg`` from planet 1's position at
t = 0.  Each angle of ``[signal] sensor_angles_from_crack_deg`` places one more
sensor at that angle from the cracked tooth's centre line (``2 pi k / z_r`` for
tooth k), in the sense of the planet angle.  Every sensor records the same
simulation through its own planet-position window (:mod:`hubvib.signal.accelerometer`),
with the same noise RMS [m/s^2] as the study's sensor, and gets its own
time-synchronous averages, indicators and non-multiple energy share.
"""
from __future__ import annotations

import math

from hubvib.signal.indicators import INDICATORS, GearOrders
from hubvib.signal.records import indicator_run, summarise
from hubvib.signal.accelerometer import sampled, sensor_signal
from hubvib.signal.spectral import non_multiple_fraction, order_spectrum


def sensor_angle(offset_from_crack_deg: float, crack_tooth: int, ring_teeth: int) -> float:
    """Sensor angle in the model's frame [rad] from its angle to the cracked tooth [deg]."""
    return 2 * math.pi * crack_tooth / ring_teeth + math.radians(offset_from_crack_deg)


def sensor_rows(sims, depths, offset_deg: float, crack_tooth: int, gear: GearOrders,
                options, tracking, points: int, noise_rms: float) -> dict:
    """One sensor: its angle and, per depth, the indicator summary and the energy share
    off the multiples of N (noise-free revolution); ``tracking`` is (the speed profile
    or None at constant speed, the carrier angle of the samples [rad])."""
    speed, sample_angle = tracking
    angle = sensor_angle(offset_deg, crack_tooth, gear.ring_teeth)
    carrier_hz = sims[0].carrier_speed / (2 * math.pi)
    duration = options.revolutions / carrier_hz
    revolutions = [sensor_signal(sim, angle, options.rigid_path)[:-1] for sim in sims]
    clean = [sampled(r, carrier_hz, options.sample_rate_hz, duration, speed)
             for r in revolutions]
    _, _, values = indicator_run(clean, sample_angle, points, gear, noise_rms,
                                 range(options.noise_seeds))
    return {"angle_from_crack_deg": offset_deg, "angle_deg": math.degrees(angle),
            "depths": [{"depth_mm": 1e3 * depth,
                        "indicators": summarise(v, INDICATORS),
                        "non_multiple_fraction": non_multiple_fraction(
                            order_spectrum(r), gear.n_planets)}
                       for depth, v, r in zip(depths, values, revolutions)]}
