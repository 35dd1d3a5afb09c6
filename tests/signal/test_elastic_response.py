"""The elastic ring's time integrator against exact solutions (synthetic ring, no FE)."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from hubvib.lumped.elastic_ring import coupled_modes, engagement
from hubvib.signal.elastic_model import elastic_time_model
from hubvib.signal.elastic_response import Operation, elastic_record, prewarped

from .elastic_fixtures import K_REST, constant_curves, raba_params, synthetic_ring

ZETA = 0.02


@pytest.fixture(scope="module")
def setup():
    from hubvib.design.presets import preset_design
    from hubvib.signal.mesh_phase import design_phasing

    design = preset_design("raba118")
    params, ring = raba_params(), synthetic_ring()
    return params, ring, constant_curves(design), design_phasing(design)


def _frozen(params, ring, tooth: int, keep_hz: float = 1e6):
    """The time model with the carrier standing with planet 1 on ``tooth``."""
    model = elastic_time_model(params, ring, K_REST, ZETA, 1000.0, keep_hz)
    return replace(model, theta=model.theta + ring.patch_angles[tooth] - model.theta[0])


def test_prewarped_trapezoid_has_the_exact_poles():
    """One mode, the trapezoidal rule with the prewarped stiffness and damping: its
    one-step pole equals exp(s h) of the continuous mode (exact, to round-off)."""
    omega, h = np.array([2 * math.pi * 8600.0]), 1 / 40000
    lam, c, _ = prewarped(omega, ZETA, h)
    A = np.array([[0.0, 1.0], [-lam[0], -c[0]]])
    step = np.linalg.solve(np.eye(2) - 0.5 * h * A, np.eye(2) + 0.5 * h * A)
    z = np.linalg.eigvals(step)
    s = -ZETA * omega[0] + 1j * omega[0] * math.sqrt(1 - ZETA ** 2)
    exact = np.exp(s * h)
    assert np.min(np.abs(z - exact)) < 1e-12, f"poles {z} vs exp(s h) = {exact}"


def test_free_decay_of_a_reference_mode_is_exact(setup):
    """Carrier standing at the reference, constant meshes: a free decay of one mode is
    that mode's exact damped oscillation, so the sampled record satisfies the exact
    two-term recursion x_(n+1) - 2 e^(-zeta w h) cos(w_d h) x_n + e^(-2 zeta w h) x_(n-1)
    = 0 (modal superposition with one mode), to round-off."""
    params, ring, curves, phasing = setup
    model = _frozen(params, ring, 0)
    j = model.modes // 2
    fs = 200e3
    start = np.zeros(model.modes)
    start[j] = 1e-3
    rec = elastic_record(model, curves, phasing, Operation(0.0, fs, 0.05, 1, run_in=0.0),
                         float(ring.patch_angles[3]), initial=(start, np.zeros(model.modes)))
    x = rec.values
    w, h = model.omega[0, j], 1 / fs
    a1 = -2 * math.exp(-ZETA * w * h) * math.cos(w * math.sqrt(1 - ZETA ** 2) * h)
    a2 = math.exp(-2 * ZETA * w * h)
    residual = x[2:] + a1 * x[1:-1] + a2 * x[:-2]
    assert np.max(np.abs(residual)) < 1e-9 * np.max(np.abs(x)), (
        f"mode {j + 1} at {model.frequency_hz(0)[j]:.6g} Hz: recursion residual "
        f"{np.max(np.abs(residual)):.3g} of peak {np.max(np.abs(x)):.3g} (exact: 0)")


def test_standing_carrier_at_rest_stays_at_rest(setup):
    """At the reference's static state with the carrier standing on the reference, no mesh
    changes and no forcing: the record is zero (the static loads balance)."""
    params, ring, curves, phasing = setup
    model = _frozen(params, ring, 0)
    rec = elastic_record(model, curves, phasing, Operation(0.0, 200e3, 0.01, 1, run_in=0.0),
                         0.3)
    assert np.max(np.abs(rec.values)) < 1e-6, f"{np.max(np.abs(rec.values)):.3g} m/s^2 (exact 0)"


def _transition_frequencies(params, ring, curves, phasing, tooth, fs, keep_hz=1e6):
    """Natural frequencies [Hz] of the integrator's one-step map ``y1 = Phi y0 + b`` with
    the carrier standing on ``tooth`` (columns of Phi from unit initial states, less b)."""
    model = _frozen(params, ring, tooth, keep_hz=keep_hz)
    m = model.modes

    def step(y):
        rec = elastic_record(model, curves, phasing, Operation(0.0, fs, 2 / fs, 1, run_in=0.0),
                             0.3, initial=(y[:m], y[m:]))
        return np.concatenate(rec.final_state)

    b = step(np.zeros(2 * m))
    columns = [step(np.eye(2 * m)[k]) - b for k in range(2 * m)]
    z = np.linalg.eigvals(np.array(columns).T)
    s = np.log(z[z.imag > 0]) * fs
    return np.sort(np.abs(s)) / (2 * math.pi)


class _Stiffer:
    """Mesh curves whose every value is ``factor`` times their mean (a constant change of
    every mesh stiffness against the mean the model was built with)."""

    def __init__(self, curves, factor):
        self.base_pitch, self.sun_mean, self.ring_mean = (curves.base_pitch, curves.sun_mean,
                                                          curves.ring_mean)
        self.factor = factor

    def sun(self, s):
        return np.full(np.shape(s), self.factor * self.sun_mean)

    def ring(self, s, s_cracked=None):
        return np.full(np.shape(s), self.factor * self.ring_mean)


def _stiffer(curves, factor):
    return _Stiffer(curves, factor)


def test_mesh_stiffness_change_moves_the_modes_as_the_eigensolution(setup):
    """Carrier standing on tooth 5 with every mesh 20 % stiffer than the mean the model
    was built with (the rank-2N correction, constant): the integrator's one-step map has
    the natural frequencies of the coupled model with those meshes (``coupled_modes``, an
    independent eigen-solution), converging at second order as the step halves."""
    params, ring, curves, phasing = setup
    tooth, factor = 5, 1.2
    stiff = params.replace(c_sp=factor * params.c_sp)
    exact = coupled_modes(stiff, ring, tooth, factor * K_REST).frequency_hz
    errors = []
    for fs in (200e3, 400e3):
        found = _transition_frequencies(params, ring, _stiffer(curves, factor), phasing,
                                        tooth, fs)
        errors.append(np.max(np.abs(found - exact) / exact))
    assert errors[1] < 2e-3, f"largest relative error {errors[1]:.3g} at h = 1/400 kHz"
    assert errors[0] / errors[1] > 3.0, (
        f"error {errors[0]:.3g} -> {errors[1]:.3g} when h halves: second order expected (4x)")


def test_high_modes_condensed_keep_the_low_ones(setup):
    """Modes above 9 kHz static (condensed into the kept ones), meshes 20 % stiffer: the
    modes below 3 kHz keep the eigen-solution's frequencies within 0.2 %."""
    params, ring, curves, phasing = setup
    tooth, factor = 5, 1.2
    exact = coupled_modes(params.replace(c_sp=factor * params.c_sp), ring, tooth,
                          factor * K_REST).frequency_hz
    found = _transition_frequencies(params, ring, _stiffer(curves, factor), phasing, tooth,
                                    400e3, keep_hz=9e3)
    low = exact < 3e3
    error = np.max(np.abs(found[:low.sum()] - exact[low]) / exact[low])
    assert error < 2e-3, f"largest relative error below 3 kHz {error:.3g} (modes > 9 kHz static)"
