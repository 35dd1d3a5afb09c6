"""The elastic ring's coupled modes identified from simulated records (synthetic ring, no FE):
the record's frequencies against the model's, and a crack's change against the modal one."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from hubvib.identification.elastic_records import (MERGE, identify_elastic_records,
                                                   mode_bands, radial_visibility,
                                                   rotating_pairs)
from hubvib.identification.records import Record
from hubvib.lumped.elastic_ring import coupled_modes
from hubvib.signal.elastic_model import elastic_time_model
from hubvib.signal.elastic_response import Operation, elastic_record

from ..signal.elastic_fixtures import K_REST, constant_curves, raba_params, synthetic_ring

ZETA = 0.02
FS = 20000.0
SENSOR = 0.7  # [rad]
TOOTH = 5
#: radial amplitude at the sensor (of the largest) of a clearly seen mode
CLEAR = 0.3


def _record(params, ring, seed: int, duration: float = 6.0) -> Record:
    """Ambient record of the coupled model with the carrier standing on ``TOOTH``
    (constant meshes: the model is the coupled model there)."""
    from hubvib.design.presets import preset_design
    from hubvib.signal.mesh_phase import design_phasing

    design = preset_design("raba118")
    model = elastic_time_model(params, ring, K_REST, ZETA, 1000.0, 15e3)
    model = replace(model, theta=model.theta + ring.patch_angles[TOOTH] - model.theta[0])
    rec = elastic_record(model, constant_curves(design), design_phasing(design),
                         Operation(0.0, FS, duration, 2, ambient_psd=1e4), SENSOR,
                         np.random.default_rng(seed))
    values = rec.values + 0.02 * rec.values.std() * np.random.default_rng(seed + 99
                                                                          ).standard_normal(
        rec.values.size)
    return Record(values, FS)


def test_bands_group_close_modes_and_leave_faint_ones_out():
    """Modes 1 and 2 of three, 0.1 half-power bandwidth apart, are one peak named by the
    one stronger at the sensor; a faint mode is not reported; a far mode has its own band."""
    f = np.array([1000.0, 1004.0, 3000.0, 5000.0])
    vis = np.array([0.3, 1.0, 0.01, 0.5])
    bands, skipped = mode_bands(f, vis, ZETA)
    assert [[g.members for g in b] for b in bands] == [[(1, 0)], [(3,)]]
    assert 2 in skipped and "not seen" in skipped[2]


def test_rotating_pairs_are_the_modes_within_merge_bandwidths():
    """At 2 % damping ``MERGE`` half-power bandwidths are 10 Hz at 1 kHz and 30 Hz at 3 kHz:
    1000/1002 Hz is a pair, 3000/3050 Hz is not, 2000 Hz is alone."""
    assert MERGE == 0.25, "the numbers below are for MERGE = 0.25"
    assert rotating_pairs([1000.0, 1002.0, 2000.0, 3000.0, 3050.0], ZETA) == {0, 1}


@pytest.mark.slow
def test_intact_and_cracked_records_give_the_models_frequencies_and_change():
    """A standing carrier (an LTI coupled model), white forces, 6 s at 20 kHz: every
    identified frequency of a clearly seen mode (``CLEAR``) alone in its band in the intact
    record lies within 3
    identification sigmas of the coupled model's (``coupled_modes``, independent of the
    integrator), and the change
    identified between the intact and the cracked record equals the modal change within 3
    of its sigmas (the root-sum-square of the two records' bounds)."""
    params = raba_params()
    intact_ring, cracked_ring = synthetic_ring(0.0), synthetic_ring(0.1)
    intact = coupled_modes(params, intact_ring, TOOTH, K_REST, max_hz=9.5e3)
    cracked = coupled_modes(params, cracked_ring, TOOTH, K_REST, max_hz=9.5e3)
    now = _record(params, cracked_ring, 1)
    base = _record(params, intact_ring, 2)
    found = identify_elastic_records(now, base, intact, SENSOR, ZETA)
    assert found.modes.size >= 3, f"identified modes {found.modes + 1}: {found.skipped_modes}"
    vis = radial_visibility(intact.probe, SENSOR)
    bands, _ = mode_bands(intact.frequency_hz, vis, ZETA)
    alone = {b[0].members[0] for b in bands if len(b) == 1 and len(b[0].members) == 1
             and vis[b[0].members[0]] >= CLEAR}
    single = [k for k, i in enumerate(found.modes) if i in alone]
    assert single, f"no clearly seen separated mode identified: {found.skipped_modes}"
    for k in single:
        i = found.modes[k]
        sigma_base = found.intact.modes[found.intact.index.index(i)].sigma_hz
        error = (found.baseline_hz[k] - intact.frequency_hz[i]) / sigma_base
        assert abs(error) < 3, (f"mode {i + 1} (visibility {vis[i]:.2g}): identified "
                                f"{found.baseline_hz[k]:.2f} Hz vs coupled_modes "
                                f"{intact.frequency_hz[i]:.2f} Hz = {error:.2g} sigma")
        change = cracked.frequency_hz[i] - intact.frequency_hz[i]
        sigma = math.sqrt(2) * found.sigma_hz[k]
        assert abs(found.shift_hz[k] - change) < 3 * sigma, (
            f"mode {i + 1}: identified change {found.shift_hz[k]:.2f} Hz vs modal change "
            f"{change:.2f} Hz (sigma {sigma:.2f} Hz)")
