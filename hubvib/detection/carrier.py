"""When the cracked ring tooth is in mesh, and what a record of length T sees (SI).

The ring is held (it carries the mounting); the carrier turns.  A ring tooth
pair stays in contact while the contact point runs along the path of contact,
``eps_alpha`` base pitches, which the carrier covers in ``eps_alpha 2 pi / z_r``
of rotation.  Each of the N planets passes the cracked tooth once per carrier
revolution, so it is in mesh for the fraction ``N eps_alpha / z_r`` of the time,
in passes of ``eps_alpha 2 pi / (z_r Omega_c)`` seconds.

A record that spans many passes sees a stiffness that switches periodically.
To first order in the (small) stiffness change, away from parametric
resonance, its natural frequencies are those of the time-averaged stiffness
matrix, ``lambda = (1 - f) lambda_out + f lambda_in`` mode by mode (averaging
method; Nayfeh & Mook, Nonlinear Oscillations, 1979, ch. 5).  A record no longer
than one pass can see the in-mesh spectrum itself, at a resolution no finer
than one over the pass duration.

The time-averaged frequency is the central line of the response; the passes add
sidebands at multiples of the pass frequency ``N Omega_c / 2 pi``.  They stay
weak while the phase a mode loses during one pass, ``|omega_in - omega_out| t_pass``
(the modulation index), is well below 1 rad; above it the mode's peak splits.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.reducer.stages import gear_body, ring_gear
from hubvib.fem.mesh_cycle import GearPair
from hubvib.lumped import natural_modes

from .mode_names import tracked, tracked_order


@dataclass(frozen=True)
class MeshTiming:
    """Engagement of the cracked ring tooth.

    Attributes
    ----------
    ring_teeth : int
        Teeth of the ring z_r.
    contact_ratio : float
        Transverse contact ratio of the ring-planet mesh eps_alpha [-].
    n_planets : int
        Planets N.
    carrier_speed : float
        Carrier speed [rad/s].
    """

    ring_teeth: int
    contact_ratio: float
    n_planets: int
    carrier_speed: float

    @property
    def engaged_fraction(self) -> float:
        """Fraction of time the cracked tooth is in mesh with some planet [-]."""
        return min(1.0, self.n_planets * self.contact_ratio / self.ring_teeth)

    @property
    def pass_angle(self) -> float:
        """Carrier rotation during one engagement of the cracked tooth [rad]."""
        return self.contact_ratio * 2 * math.pi / self.ring_teeth

    @property
    def pitch_angle(self) -> float:
        """Carrier rotation while the mesh advances by one ring tooth [rad]."""
        return 2 * math.pi / self.ring_teeth

    @property
    def pass_seconds(self) -> float:
        """Duration of one engagement [s]."""
        return self.pass_angle / self.carrier_speed

    @property
    def pass_frequency(self) -> float:
        """How often a planet passes the cracked tooth, N Omega_c / (2 pi) [Hz]: the
        spacing of the sidebands a passing planet puts around every mode."""
        return self.n_planets * self.carrier_speed / (2 * math.pi)

    def long_record(self, record_length: float) -> bool:
        """True when a record of ``record_length`` [s] spans more than one pass, so it
        sees the time-averaged spectrum."""
        return record_length > self.pass_seconds


def mesh_timing(design, carrier_speed: float) -> MeshTiming:
    """Timing of the ring-planet mesh of a ``ReducerDesign`` (as the FE stage builds it)
    at ``carrier_speed`` [rad/s]."""
    ring = ring_gear(design)
    pair = GearPair(gear_body(design, "planet"), ring)
    return MeshTiming(int(ring.teeth), float(pair.contact_ratio), int(design.n_planets),
                      float(carrier_speed))


def observed_eigenvalues(lam_in: np.ndarray, lam_out: np.ndarray, fraction: float,
                         long_record: bool) -> np.ndarray:
    """Eigenvalues [rad^2/s^2] a record sees: the in-mesh ones for a record within one
    pass, else the time average ``(1 - fraction) lam_out + fraction lam_in``."""
    if not long_record:
        return np.asarray(lam_in)
    return (1.0 - fraction) * np.asarray(lam_out) + fraction * np.asarray(lam_in)


def observed_omega(omega_in: np.ndarray, omega_out: np.ndarray, fraction: float,
                   long_record: bool) -> np.ndarray:
    """Natural frequencies [rad/s] a record sees (see :func:`observed_eigenvalues`)."""
    return np.sqrt(observed_eigenvalues(np.square(omega_in), np.square(omega_out), fraction,
                                        long_record))


@dataclass(frozen=True)
class CarrierStudy:
    """Spectra in and out of engagement and over one passage of planet 1.

    Attributes
    ----------
    timing : MeshTiming
    record_length : float
        [s]
    omega_in, omega_out, omega_observed : ndarray, shape (depths, modes)
        Natural frequencies [rad/s] with planet 1 on the cracked tooth, with no planet
        on it, and as a record of ``record_length`` sees them.
    angle : ndarray
        Carrier angle from the start of planet 1's engagement [rad], over one passage.
    omega_angle, omega_angle_min : ndarray, shape (angles, modes)
        Frequencies [rad/s] at the deepest crack against the carrier angle, with the
        cracked mesh at its FE mean ratio over the engagement and at its minimum ratio.
    """

    @property
    def modulation_index(self) -> np.ndarray:
        """Phase [rad] each mode loses during one pass, shape (depths, modes)."""
        return np.abs(self.omega_in - self.omega_out) * self.timing.pass_seconds

    timing: MeshTiming
    record_length: float
    omega_in: np.ndarray
    omega_out: np.ndarray
    omega_observed: np.ndarray
    angle: np.ndarray
    omega_angle: np.ndarray
    omega_angle_min: np.ndarray


def carrier_study(model, timing: MeshTiming, record_length: float,
                  points_per_pitch: int = 40) -> CarrierStudy:
    """Spectra of ``model`` (a CrackModel) in and out of engagement, per depth, and over
    one passage of planet 1 at the deepest crack."""
    depths = range(len(model.depths))
    spectra_in = [natural_modes(model.parameters(k, True), model.method) for k in depths]
    spectra_out = [natural_modes(model.parameters(k, False), model.method) for k in depths]
    omega_in = tracked(np.array([s.omega for s in spectra_in]), tracked_order(spectra_in))
    omega_out = tracked(np.array([s.omega for s in spectra_out]), tracked_order(spectra_out))
    observed = observed_omega(omega_in, omega_out, timing.engaged_fraction,
                              timing.long_record(record_length))
    pitch = timing.pitch_angle
    angle = np.linspace(-0.5 * pitch, timing.pass_angle + 0.5 * pitch,
                        int(points_per_pitch * (timing.contact_ratio + 1)) + 1)
    inside = (angle >= 0) & (angle <= timing.pass_angle)
    deepest = len(model.depths) - 1
    low = model.parameters(deepest, True).replace(
        c_rp_factors=(float(model.c_rp_factor(deepest, minimum=True)),)
        + (1.0,) * (model.params.n_planets - 1))
    omega_min = natural_modes(low, model.method).omega
    omega_angle = np.where(inside[:, None], omega_in[deepest], omega_out[deepest])
    omega_angle_min = np.where(inside[:, None], omega_min, omega_out[deepest])
    return CarrierStudy(timing, record_length, omega_in, omega_out, observed, angle,
                        omega_angle, omega_angle_min)
