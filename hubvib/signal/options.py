"""The ``[signal]`` table of a scene: operating point, sensor and analysis settings (SI).

Scene keys (all optional; defaults shown)::

    [signal]
    sun_speed_rpm = 1500.0        # input (sun) speed [min^-1]; the carrier turns at
                                  # z_s / (z_s + z_r) of it, the ring is fixed
    sun_torque_N_m = 1000.0       # input torque on the sun [N m] (sets the mesh load)
    revolutions = 10.0            # recorded duration in carrier revolutions (>= 2)
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
    indicator_max_order = 0       # highest carrier order the indicators see (0: all)
    planet_position_errors_m = [] # carrier pin-hole tangential error of each planet [m]
    pin_hole_radial_errors_m = [] # carrier pin-hole radial error of each planet [m]
    ring_runout_m = 0.0           # eccentricity of the ring teeth about the carrier axis [m]
    ring_runout_phase_deg = 0.0   # its direction, fixed in space [deg]
    contact = "piecewise"         # a mesh that would pull separates; "linear": it may pull
    sensor_angles_from_crack_deg = []  # more sensors, at these angles from the cracked tooth
    roc_records = 100             # records per depth for ROC / POD (0: none); 3x for training
    speed_fluctuation = 0.0       # relative amplitude of a sinusoidal carrier-speed fluctuation
    speed_fluctuation_hz = 1.0    # its frequency [Hz]; the record is order-tracked by the tacho
    tacho_pulses_per_revolution = 16  # pulses of the carrier encoder per revolution
    false_alarm_rate = 0.05       # family-wise false-alarm rate of the POD thresholds
    ambient_force_psd_N2_Hz = 0.0 # one-sided PSD of broadband random forces on the nine
                                  # central coordinates, added to the written records (0: none)
    ambient_seed = 0              # seed of the ambient forcing

Every check that needs only the table and the Raba gear data (the mesh frequency) is
made here; the time-step stability check needs the model and is made before the
integration starts (:func:`hubvib.signal.dynamics.check_time_step`).
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from hubvib.foundation.errors import SceneError
from hubvib.foundation.schema import Field, Schema
from hubvib.signal.mesh_phase import design_teeth

from .errors import StageErrors

MESH_STIFFNESS = ("ratio", "direct")
INTEGRATORS = ("newmark", "central")
CONTACT = ("piecewise", "linear")


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
        Recorded duration in carrier revolutions [-], >= 2 (the samples end one sample
        before the duration, and the time-synchronous average takes the whole
        revolutions among them).
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
    indicator_max_order : int
        Highest carrier order kept in the indicators [-] (0: every order of the TSA).
    planet_position_errors_m, pin_hole_radial_errors_m : tuple of float
        Carrier pin-hole errors, one per planet (tangential, radial) [m]; empty: none.
    ring_runout_m : float
        Ring run-out (eccentricity) [m], >= 0.
    ring_runout_phase_deg : float
        Direction of the ring run-out [deg].
    contact : str
        ``"piecewise"``: mesh stiffness 0 where a tooth pair would carry tension
        (:mod:`hubvib.signal.contact`); ``"linear"``: the springs may pull.
    sensor_angles_from_crack_deg : tuple of float
        Further sensors, each at this angle from the cracked tooth [deg]
        (:mod:`hubvib.signal.sensors`).
    roc_records : int
        Evaluation records per depth of the detection rates [-] (0: none;
        :mod:`hubvib.signal.roc`).
    false_alarm_rate : float
        Family-wise false-alarm rate of the POD thresholds [-], in (0, 0.5).
    speed_fluctuation : float
        Relative amplitude of the carrier-speed fluctuation [-], in [0, 0.5]
        (:mod:`hubvib.signal.speed`).
    speed_fluctuation_hz : float
        Frequency of the fluctuation [Hz], > 0.
    tacho_pulses_per_revolution : int
        Pulses of the carrier tacho (encoder) per revolution [-], 1..4096.
    ambient_force_psd_N2_Hz, ambient_seed : float, int
        White broadband forcing of the written records (:mod:`hubvib.signal.ambient`):
        one-sided PSD [N^2/Hz] and seed.
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
    indicator_max_order: int = 0
    planet_position_errors_m: tuple[float, ...] = ()
    pin_hole_radial_errors_m: tuple[float, ...] = ()
    ring_runout_m: float = 0.0
    ring_runout_phase_deg: float = 0.0
    contact: str = "piecewise"
    sensor_angles_from_crack_deg: tuple[float, ...] = ()
    roc_records: int = 100
    false_alarm_rate: float = 0.05
    speed_fluctuation: float = 0.0
    speed_fluctuation_hz: float = 1.0
    tacho_pulses_per_revolution: int = 16
    ambient_force_psd_N2_Hz: float = 0.0
    ambient_seed: int = 0

    @property
    def errors(self) -> StageErrors:
        """The manufacturing errors of the stage (SI)."""
        return StageErrors(self.planet_position_errors_m, self.pin_hole_radial_errors_m,
                           self.ring_runout_m, math.radians(self.ring_runout_phase_deg))

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


_DEG = "deg"
#: the ``[signal]`` keys in the order of the module docstring; a new key = one entry here
#: and its attribute in ``SignalOptions``
SCHEMA = Schema("signal", (
    Field("sun_speed_rpm", "number", 0.0, math.inf, True, True, default=1500.0,
          unit="min^-1", doc="input (sun) speed; the carrier turns at z_s / (z_s + z_r) of it"),
    Field("sun_torque_N_m", "number", 0.0, math.inf, True, True, default=1000.0, unit="N m",
          doc="input torque on the sun (sets the mesh load)"),
    # >= 2: the samples run 0 <= t < duration, so one revolution is a sample short of the
    # whole revolution the time-synchronous average needs (1 failed after all the work)
    Field("revolutions", "number", 2.0, 1e4, default=10.0, unit="-",
          doc="recorded duration in carrier revolutions"),
    Field("sample_rate_hz", "number", 0.0, 1e7, True, False, default=20000.0, unit="Hz",
          doc="at least 2 x mesh_harmonics x mesh frequency"),
    Field("mesh_harmonics", "integer", 1, 50, default=3, unit="-",
          doc="highest mesh harmonic analysed (indicators, checks)"),
    Field("sensor_angle_deg", "number", -math.inf, math.inf, True, True, default=0.0,
          unit=_DEG, doc="accelerometer position on the ring, from planet 1 at t = 0"),
    Field("damping_ratio", "number", 0.0, 1.0, False, True, default=0.05, unit="-",
          doc="modal damping of every mode"),
    Field("noise_level", "number", 0.0, 10.0, default=0.05, unit="-",
          doc="white noise RMS / RMS of the intact signal"),
    Field("noise_seeds", "integer", 1, 100, default=5, unit="-",
          doc="noise realisations per depth"),
    Field("rigid_path", "number", 0.0, 1e6, default=0.0, unit="-",
          doc="weight of the ring's rigid-body acceleration path"),
    Field("mesh_stiffness", "choice", choices=MESH_STIFFNESS, default="ratio",
          doc="ratio: FE curve shape scaled to the preset's mean c_sp, c_rp; direct: FE values"),
    Field("transmission_error_m", "number", 0.0, 1e-3, default=0.0, unit="m",
          doc="amplitude of a first-harmonic static TE per mesh"),
    Field("integrator", "choice", choices=INTEGRATORS, default="newmark",
          doc="newmark: average acceleration; central: explicit, for checks"),
    Field("steps_per_period", "integer", 4, 1000, default=20, unit="-",
          doc="time steps per period of the highest mode"),
    Field("time_step_s", "number", 0.0, 1.0, default=0.0, unit="s",
          doc="0: chosen from steps_per_period and the mesh period"),
    Field("indicator_max_order", "integer", 0, 100000, default=0, unit="-",
          doc="highest carrier order the indicators see (0: all)"),
    Field("planet_position_errors_m", "numbers", -1e-3, 1e-3, default=[],
          unit="[m], one per planet", doc="carrier pin-hole tangential error of each planet"),
    Field("pin_hole_radial_errors_m", "numbers", -1e-3, 1e-3, default=[],
          unit="[m], one per planet", doc="carrier pin-hole radial error of each planet"),
    Field("ring_runout_m", "number", 0.0, 1e-3, default=0.0, unit="m",
          doc="eccentricity of the ring teeth about the carrier axis"),
    Field("ring_runout_phase_deg", "number", -math.inf, math.inf, True, True, default=0.0,
          unit=_DEG, doc="direction of the run-out, fixed in space"),
    Field("contact", "choice", choices=CONTACT, default="piecewise",
          doc="piecewise: a mesh that would pull separates; linear: it may pull"),
    Field("sensor_angles_from_crack_deg", "numbers", -360.0, 360.0, default=[],
          unit="[deg]", doc="more sensors, at these angles from the cracked tooth"),
    Field("roc_records", "integer", 0, 10000, default=100, unit="-",
          doc="records per depth for ROC / POD (0: none); 3x for training"),
    Field("speed_fluctuation", "number", 0.0, 0.5, default=0.0, unit="-",
          doc="relative amplitude of a sinusoidal carrier-speed fluctuation"),
    Field("speed_fluctuation_hz", "number", 0.0, 1e3, True, False, default=1.0, unit="Hz",
          doc="its frequency; the record is order-tracked by the tacho"),
    Field("tacho_pulses_per_revolution", "integer", 1, 4096, default=16, unit="-",
          doc="pulses of the carrier encoder per revolution"),
    Field("false_alarm_rate", "number", 0.0, 0.5, True, True, default=0.05, unit="-",
          doc="family-wise false-alarm rate of the POD thresholds"),
    Field("ambient_force_psd_N2_Hz", "number", 0.0, 1e12, default=0.0, unit="N^2/Hz",
          doc="one-sided PSD of broadband random forces on the nine central coordinates, "
              "added to the written records (0: none)"),
    Field("ambient_seed", "integer", 0, 2 ** 32 - 1, default=0, unit="-",
          doc="seed of the ambient forcing"),
), number="a finite number")


def parse_signal_table(table: dict) -> SignalOptions:
    """Validate a ``[signal]`` table into :class:`SignalOptions` (``SCHEMA``).

    Raises
    ------
    hubvib.foundation.errors.SceneError
        Naming ``[signal] key``, the value and the allowed range.
    """
    return SignalOptions(**SCHEMA.parse(table))


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
