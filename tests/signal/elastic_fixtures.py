"""A small synthetic elastic ring coupled to the Raba lumped model, for the time-response
and identification tests (no FE): 8 ring coordinates with M = I, 16 teeth, a probe of 16
points, a crack that softens the ring along one shape."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from hubvib.lumped.elastic_ring import RingOperators

TEETH = 16
K_REST = 2e9


def synthetic_ring(crack: float = 0.0, seed: int = 3) -> RingOperators:
    """Ring modes at 1.5-9 kHz; ``crack`` in [0, 1] lowers one shape's stiffness by up to
    15 % of the fourth mode's."""
    rng = np.random.default_rng(seed)
    n, probe_points = 8, 16
    q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    omega = 2 * math.pi * np.linspace(1500.0, 9000.0, n)
    K = q @ np.diag(omega ** 2) @ q.T
    shape = rng.standard_normal(n)
    K = K - crack * np.outer(shape, shape) / (shape @ shape) * 0.15 * omega[3] ** 2
    angles = 2 * math.pi * (np.arange(TEETH) + 0.25) / TEETH
    directions = np.column_stack([-np.sin(angles), np.cos(angles)])
    contact = rng.standard_normal((n, TEETH)) * 1e-1
    probe = rng.standard_normal((2 * probe_points, n))
    return RingOperators(0.5 * (K + K.T), np.eye(n), contact, np.ones(TEETH), angles,
                         directions, probe)


def raba_params():
    from hubvib.design.presets import preset_design
    from hubvib.reducer.stages import lumped_parameters

    return lumped_parameters(preset_design("raba118"))


def constant_curves(design):
    """The design's synthetic mesh curves made constant (their means)."""
    from hubvib.signal.mesh_curves import synthetic_curves

    c = synthetic_curves(design)
    return replace(c, sun_k=np.full_like(c.sun_k, c.sun_mean),
                   ring_k=np.full_like(c.ring_k, c.ring_mean))
