"""The ``[signal]`` table of a scene: operating point, sensor and analysis settings (SI).

Scene keys (all optional; defaults shown)::

    [signal]
    sun_speed_rpm = 1500.0        # input (sun) speed [min^-1]; the carrier turns at
                                  # z_s / (z_s + z_r) of it, the ring is fixed
    sun_torque_N_m = 1000.0       # input torque on the sun [N m] (sets the mesh load)
    revolutions = 10.0            # recorded duration in carrier revolutions (>= 1)
    sample_rate_hz = 20000.0      # >= 2 x mesh_harmonics x mesh frequency
    mesh_harmonics = 3            # highest mesh harmonic analysed (indicators, checks)
    sensor_angle_deg = 0.0        # accelerometer position on the ring, from planet 1's
                                  # position at t = 0 (the cracked tooth sits at its own angle)
    damping_ratio = 0.05          # modal damping of every mode, in [0, 1)
    noise_level = 0.05            # white noise RMS / RMS of the intact signal
    noise_seeds = 5               # noise realisations per depth (spread of the intact value)
    rigid_path = 0.0              # weight of the ring's rigid-body acceleration path [-]
    mesh_stiffness = "ratio"      # FE curve shape scaled to the preset's mean c_sp, c_rp;
                                  # "direct": the FE values themselves
    transmission_error_m = 0.0    # amplitude of a first-harmonic static TE per mesh [m]
    integrator = "newmark"        # average acceleration; "central" (explicit, for checks)
    steps_per_period = 20         # time steps per period of the highest mode
    time_step_s = 0.0             # 0: chosen from steps_per_period and the mesh period

Every check that needs only the table and the Raba gear data (the mesh frequency) is
made here; the time-step stability check needs the model and is made before the
integration starts (:func:`hubvib.signal.dynamics.check_time_step`).
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from hubvib.foundation.errors import SceneError
from hubvib.signal.mesh_phase import design_teeth

MESH_STIFFNESS = ("ratio", "direct")
INTEGRATORS = ("newmark", "central")


@dataclass(frozen=True)
class SignalOptions:
    """Settings of the vibration-signature study (SI inside; names carry the edge units).

    Attributes
    ----------
    sun_speed_rpm : float
        Input speed of the sun [min^-1], > 0.
    sun_torque_N_m : float
        Input torque on the sun [N m], > 0.
    revolutions : float
        Recorded duration in carrier revolutions [-], >= 1 (rounded down to whole
        revolutions for the time-synchronous average).
    sample_rate_hz : float
        Sample rate of the sensor signal [Hz].
    mesh_harmonics : int
        Highest mesh harmonic analysed [-], >= 1.
    sensor_angle_deg : float
        Sensor position on the ring [deg], finite.
    damping_ratio : float
        Modal damping ratio of every mode [-], in [0, 1).
    noise_level : float
        RMS of the added white noise as a fraction of the intact signal's RMS [-], >= 0.
    noise_seeds : int
        Noise realisations per crack depth [-], >= 1.
    rigid_path : float
        Weight of the ring's rigid-body (translational) acceleration at the sensor [-], >= 0.
    mesh_stiffness : str
        ``"ratio"`` or ``"direct"`` (see the module docstring).
    transmission_error_m : float
        First-harmonic static transmission error amplitude of every mesh [m], >= 0.
    integrator : str
        ``"newmark"`` (average acceleration) or ``"central"`` (explicit central difference).
    steps_per_period : int
        Time steps per period of the highest natural frequency [-], >= 4.
    time_step_s : float
        Explicit time step [s]; 0 chooses it (see ``steps_per_period``).
    """

    sun_speed_rpm: float = 1500.0
    sun_torque_N_m: float = 1000.0
    revolutions: float = 10.0
    sample_rate_hz: float = 20000.0
    mesh_harmonics: int = 3
    sensor_angle_deg: float = 0.0
    damping_ratio: float = 0.05
    noise_level: float = 0.05
    noise_seeds: int = 5
    rigid_path: float = 0.0
    mesh_stiffness: str = "ratio"
    transmission_error_m: float = 0.0
    integrator: str = "newmark"
    steps_per_period: int = 20
    time_step_s: float = 0.0

    @property
    def sensor_angle(self) -> float:
        """Sensor angle [rad]."""
        return math.radians(self.sensor_angle_deg)

    @property
    def sun_speed(self) -> float:
        """Sun speed [rad/s]."""
        return self.sun_speed_rpm * 2 * math.pi / 60

    def to_dict(self) -> dict:
        return asdict(self)

    def check_design(self, design) -> None:
        """Checks that need the scene's design (the mesh frequency)."""
        check_sample_rate(self, design)


def kinematics(sun_speed_rpm: float, design) -> tuple[float, float]:
    """Carrier and ring-mesh frequency [Hz] at this sun speed, for a design (ring fixed:
    f_c = f_s z_s / (z_s + z_r), f_mesh = z_r f_c)."""
    teeth = design_teeth(design)
    carrier = sun_speed_rpm / 60 * teeth["sun"] / (teeth["sun"] + teeth["ring"])
    return carrier, teeth["ring"] * carrier


_NUMBERS = {  # key: (low, high, low closed, high closed)
    "sun_speed_rpm": (0.0, math.inf, False, False),
    "sun_torque_N_m": (0.0, math.inf, False, False),
    "revolutions": (1.0, 1e4, True, True),
    "sample_rate_hz": (0.0, 1e7, False, True),
    "sensor_angle_deg": (-math.inf, math.inf, False, False),
    "damping_ratio": (0.0, 1.0, True, False),
    "noise_level": (0.0, 10.0, True, True),
    "rigid_path": (0.0, 1e6, True, True),
    "transmission_error_m": (0.0, 1e-3, True, True),
    "time_step_s": (0.0, 1.0, True, True),
}
_INTEGERS = {"mesh_harmonics": (1, 50), "noise_seeds": (1, 100), "steps_per_period": (4, 1000)}
_CHOICES = {"mesh_stiffness": MESH_STIFFNESS, "integrator": INTEGRATORS}


def parse_signal_table(table: dict) -> SignalOptions:
    """Validate a ``[signal]`` table into :class:`SignalOptions`.

    Raises
    ------
    hubvib.foundation.errors.SceneError
        Naming ``[signal] key``, the value and the allowed range.
    """
    allowed = set(_NUMBERS) | set(_INTEGERS) | set(_CHOICES)
    unknown = set(table) - allowed
    if unknown:
        raise SceneError(f"unknown key(s) {sorted(unknown)} at [signal]; allowed: "
                         f"{sorted(allowed)}")
    values = {}
    for key, (low, high, low_closed, high_closed) in _NUMBERS.items():
        if key not in table:
            continue
        value = table[key]
        ok = (not isinstance(value, bool) and isinstance(value, (int, float))
              and math.isfinite(value)
              and (value > low or (low_closed and value == low))
              and (value < high or (high_closed and value == high)))
        if not ok:
            left, right = "[" if low_closed else "(", "]" if high_closed else ")"
            raise SceneError(f"[signal] {key} = {value!r}; allowed: a finite number in "
                             f"{left}{low:g}, {high:g}{right}")
        values[key] = float(value)
    for key, (low, high) in _INTEGERS.items():
        if key not in table:
            continue
        value = table[key]
        if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
            raise SceneError(f"[signal] {key} = {value!r}; allowed: an integer in {low}..{high}")
        values[key] = value
    for key, choices in _CHOICES.items():
        if key in table and table[key] not in choices:
            raise SceneError(f"[signal] {key} = {table[key]!r}; allowed: {', '.join(choices)}")
        if key in table:
            values[key] = table[key]
    options = SignalOptions(**values)
    return options


def check_sample_rate(options: SignalOptions, design) -> None:
    """Refuse a sample rate below twice the highest mesh harmonic asked for (aliasing);
    the mesh frequency is the design's."""
    _, mesh = kinematics(options.sun_speed_rpm, design)
    needed = 2 * options.mesh_harmonics * mesh
    if options.sample_rate_hz < needed:
        raise SceneError(
            f"[signal] sample_rate_hz = {options.sample_rate_hz:g}; allowed: >= {needed:.6g} Hz "
            f"(twice mesh harmonic {options.mesh_harmonics} at {mesh:.6g} Hz mesh frequency, "
            f"else it aliases)")
