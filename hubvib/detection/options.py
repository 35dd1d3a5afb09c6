"""The scene's ``[detection]`` table: what decides whether a frequency shift is detectable.

All keys, with their defaults::

    [detection]
    record_length_s = 10.0              # one record; frequency resolution 1/T [Hz]
    damping_ratio = 0.02                # ASSUMED modal damping of every mode [-]
    snr = 100.0                         # modal signal-to-noise ratio of the records [-]
    watched_modes = 4                   # modes watched together (the alarm family)
    false_alarm_rate = 0.01             # family-wise over the watched modes; in diagnose,
                                        # the rate of crack verdicts on an intact reducer
    fit_false_alarm_rate = 0.01         # rate at which diagnose calls a pattern a ring crack
                                        # does produce "not explained by a ring crack"
    temperature_std_K = 1.0             # ASSUMED: temperature change between two records [K]
    modulus_per_K = -2.6e-4             # steel: relative change of Young's modulus per K
    expansion_per_K = 1.2e-5            # steel: linear thermal expansion per K
    mesh_load_std_percent = 0.0         # change of every mesh stiffness between the records
                                        # from a load change (std, percent): 0 = records
                                        # at the same torque
    detection_probability = 0.9         # POD at which a depth counts as detectable
    scatter_masses_percent = 2.0        # relative standard deviation of every mass
    scatter_stiffnesses_percent = 10.0  # ... of mesh, bearing and sun/carrier torsion springs
    scatter_mounting_percent = 30.0     # ... of the ring mounting (c_ru, c_r mounts)
    samples = 2000                      # Monte Carlo samples per depth (POD, diagnosis)
    map_samples = 200                   # ... per mounting stiffness of the detectability map
    seed = 0
    mount_min_N_m = 1e6                 # mounting stiffness sweep of the map, log-spaced
    mount_max_N_m = 1e12
    mount_points = 13
    carrier_speed_rpm = 150.0           # ASSUMED: ~28 km/h on a 0.5 m wheel
    confidence = 0.9                    # two-sided interval of ``hubvib diagnose``

An identified natural frequency scatters by the Cramer-Rao bound of the shipped
identification method (:func:`hubvib.identification.law.fisher_sigma_hz`; Au's
law ``sqrt(zeta f / (2 pi T))`` for high SNR and a wide band) with the damping
``damping_ratio``, the record length ``record_length_s`` and the modal SNR
``snr``; a Monte Carlo of identified simulated records checks it
(``python -m hubvib.identification.montecarlo``).  The alarm family is the
``watched_modes`` modes with the largest deepest-crack shift against that scatter;
each mode's threshold holds the per-mode rate ``1 - (1 - alpha)^(1/m)`` (Sidak:
the identification errors are independent), so the family raises a false alarm
with probability ``false_alarm_rate``.  Drift between the two records (uniform
temperature, load on the meshes; :mod:`hubvib.detection.drift`) is reported as
an extra family POD, with and without compensation by reference modes, and
enters the covariance of ``hubvib diagnose``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from hubvib.foundation.errors import SceneError
from hubvib.foundation.schema import Field, Schema
from hubvib.identification.law import fisher_sigma_hz


@dataclass(frozen=True)
class DetectionOptions:
    """How a measured frequency shift is judged (SI).

    Attributes
    ----------
    record_length : float
        Length T of one vibration record [s]; frequency resolution 1/T [Hz].
    damping_ratio : float
        Modal damping ratio [-] of every mode (the measured CSV may give one per mode).
    snr : float
        Modal signal-to-noise ratio of the records, response PSD at resonance over
        the noise PSD [-].
    watched_modes : int
        Number of modes watched together: the family of the false-alarm rate.
    false_alarm_rate : float
        Probability [-] that an intact reducer raises an alarm on any watched mode
        (family-wise); in ``hubvib diagnose``, that it is called cracked.
    fit_false_alarm_rate : float
        Probability [-] that ``hubvib diagnose`` calls a frequency pattern that a ring
        crack does produce "not explained by a ring crack".
    temperature_std : float
        Standard deviation of the uniform temperature change between two records [K].
    modulus_per_K, expansion_per_K : float
        Relative change of Young's modulus and of every length per K [1/K].
    mesh_load_std : float
        Standard deviation of the common relative change of every mesh stiffness between
        two records from a load change [-].
    detection_probability : float
        Probability of detection [-] at which a depth counts as detectable.
    scatter_masses, scatter_stiffnesses, scatter_mounting : float
        Relative standard deviations [-] of the masses, of the springs other than the
        ring mounting, and of the ring mounting (log-normal, independent).
    samples, map_samples : int
        Monte Carlo samples per depth (POD, diagnosis) and per mounting stiffness (map).
    seed : int
        Seed of the random generator (results repeat exactly).
    mount_min, mount_max : float
        Range of the mounting stiffness swept by the detectability map [N/m].
    mount_points : int
        Log-spaced mounting stiffnesses in that range.
    carrier_speed : float
        Carrier speed [rad/s] (ASSUMED 150 rpm by default).
    confidence : float
        Level of the two-sided depth interval of a diagnosis [-].
    """

    record_length: float = 10.0
    damping_ratio: float = 0.02
    snr: float = 100.0
    watched_modes: int = 4
    false_alarm_rate: float = 0.01
    fit_false_alarm_rate: float = 0.01
    temperature_std: float = 1.0
    modulus_per_K: float = -2.6e-4
    expansion_per_K: float = 1.2e-5
    mesh_load_std: float = 0.0
    detection_probability: float = 0.9
    scatter_masses: float = 0.02
    scatter_stiffnesses: float = 0.10
    scatter_mounting: float = 0.30
    samples: int = 2000
    map_samples: int = 200
    seed: int = 0
    mount_min: float = 1e6
    mount_max: float = 1e12
    mount_points: int = 13
    carrier_speed: float = 150.0 * 2 * math.pi / 60
    confidence: float = 0.9

    @property
    def resolution_hz(self) -> float:
        """Frequency resolution 1/T [Hz]."""
        return 1.0 / self.record_length

    def sigma_hz(self, frequency_hz, record_length: float | None = None) -> np.ndarray:
        """Standard deviation [Hz] of frequencies ``frequency_hz`` [Hz] identified from one
        record of ``record_length`` [s] (default the scene's), per mode."""
        T = self.record_length if record_length is None else record_length
        return np.array([fisher_sigma_hz(f, self.damping_ratio, T, self.snr)
                         for f in np.atleast_1d(frequency_hz)])

    def per_mode_rate(self, modes: int | None = None) -> float:
        """Per-mode false-alarm rate [-] that gives ``false_alarm_rate`` over ``modes``
        independent modes (default ``watched_modes``): ``1 - (1 - alpha)^(1/m)``."""
        m = self.watched_modes if modes is None else modes
        return 1.0 - (1.0 - self.false_alarm_rate) ** (1.0 / m)

    def to_dict(self) -> dict:
        return {f.name: getattr(self, f.name) for f in fields(self)}


_PERCENT = 0.01
_RPM = 2 * math.pi / 60


def _number(key, low, high, open_low, open_high, default, unit, doc, attr=None, scale=1.0):
    return Field(key, "number", low, high, open_low, open_high, default=default, unit=unit,
                 doc=doc, attr=attr, scale=scale)


def _integer(key, low, high, default, doc):
    return Field(key, "integer", low, high, default=default, unit="-", doc=doc)


#: the ``[detection]`` keys, each with its attribute of ``DetectionOptions`` and the factor
#: to SI; a new key = one entry here and its attribute
SCHEMA = Schema("detection", (
    _number("record_length_s", 0.0, math.inf, True, True, 10.0, "s",
            "one record; frequency resolution 1/T", "record_length"),
    _number("damping_ratio", 0.0, 0.5, True, True, 0.02, "-",
            "ASSUMED modal damping of every mode"),
    _number("snr", 0.0, math.inf, True, True, 100.0, "-",
            "modal signal-to-noise ratio of the records"),
    _integer("watched_modes", 1, 1000, 4, "modes watched together (the alarm family)"),
    _number("false_alarm_rate", 0.0, 0.5, True, True, 0.01, "-",
            "family-wise over the watched modes; in diagnose, the rate of crack verdicts "
            "on an intact reducer"),
    _number("fit_false_alarm_rate", 0.0, 0.5, True, True, 0.01, "-",
            "rate at which diagnose calls a pattern a ring crack does produce "
            "'not explained by a ring crack'"),
    _number("temperature_std_K", 0.0, 100.0, False, False, 1.0, "K",
            "ASSUMED: temperature change between two records", "temperature_std"),
    _number("modulus_per_K", -0.01, 0.0, False, False, -2.6e-4, "1/K",
            "steel: relative change of Young's modulus per K"),
    _number("expansion_per_K", 0.0, 0.001, False, False, 1.2e-5, "1/K",
            "steel: linear thermal expansion per K"),
    _number("mesh_load_std_percent", 0.0, 100.0, False, False, 0.0, "%",
            "std of the change of every mesh stiffness between the records from a load "
            "change (0: same torque)", "mesh_load_std", _PERCENT),
    _number("detection_probability", 0.0, 1.0, True, True, 0.9, "-",
            "POD at which a depth counts as detectable"),
    _number("scatter_masses_percent", 0.0, 100.0, False, False, 2.0, "%",
            "relative standard deviation of every mass", "scatter_masses", _PERCENT),
    _number("scatter_stiffnesses_percent", 0.0, 100.0, False, False, 10.0, "%",
            "... of mesh, bearing and sun/carrier torsion springs", "scatter_stiffnesses",
            _PERCENT),
    _number("scatter_mounting_percent", 0.0, 100.0, False, False, 30.0, "%",
            "... of the ring mounting (c_ru, c_r mounts)", "scatter_mounting", _PERCENT),
    _integer("samples", 100, 1_000_000, 2000, "Monte Carlo samples per depth (POD, diagnosis)"),
    _integer("map_samples", 20, 100_000, 200,
             "... per mounting stiffness of the detectability map"),
    _integer("seed", 0, 2**63 - 1, 0, "seed of the random generator"),
    _number("mount_min_N_m", 0.0, math.inf, True, True, 1e6, "N/m",
            "mounting stiffness sweep of the map, log-spaced, from", "mount_min"),
    _number("mount_max_N_m", 0.0, math.inf, True, True, 1e12, "N/m", "... to", "mount_max"),
    _integer("mount_points", 2, 200, 13, "... in this many points"),
    _number("carrier_speed_rpm", 0.0, 1e5, True, False, 150.0, "min^-1",
            "ASSUMED: ~28 km/h on a 0.5 m wheel", "carrier_speed", _RPM),
    _number("confidence", 0.0, 1.0, True, True, 0.9, "-",
            "two-sided interval of hubvib diagnose"),
), integers="interval")


def parse_detection_table(table: dict) -> DetectionOptions:
    """Validate a ``[detection]`` table (``SCHEMA``); raise SceneError naming the key, value
    and range."""
    options = DetectionOptions(**SCHEMA.parse(table))
    if options.mount_min >= options.mount_max:
        raise SceneError(f"[detection] mount_min_N_m = {options.mount_min:g} must be below "
                         f"mount_max_N_m = {options.mount_max:g}")
    if options.detection_probability <= options.false_alarm_rate:
        raise SceneError(f"[detection] detection_probability = "
                         f"{options.detection_probability:g} must exceed false_alarm_rate = "
                         f"{options.false_alarm_rate:g}")
    return options


def detection_options(scene) -> DetectionOptions:
    """The scene's ``[detection]`` options, or the documented defaults."""
    return scene.detection
