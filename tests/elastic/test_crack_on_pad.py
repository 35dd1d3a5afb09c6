"""The FE ring's own modes with the crack on a clamped support pad and between pads."""
from __future__ import annotations

import math

import numpy as np
import pytest


def _ring_hz(design, crack, options, tooth: int) -> np.ndarray:
    """The reduced ring's own frequencies [Hz], ascending (its stiffness with M = I)."""
    from hubvib.elastic.model import elastic_ring

    K = elastic_ring(design, crack, False, options, (tooth,)).operators.K
    return np.sqrt(np.clip(np.linalg.eigvalsh(0.5 * (K + K.T)), 0.0, None)) / (2 * math.pi)


@pytest.mark.slow
def test_a_crack_mid_pad_hardly_moves_the_clamped_rings_fundamental_one_mid_span_does():
    """Raba ring clamped on its six 20 deg pads, a 6 mm root crack at tooth 0 (mouth 2.5
    deg from pad 0's middle) and at its counterpart tooth 5 (0.6 deg from the middle of
    the 40 deg span beside it).  The fundamental (the spans bending in phase) is a
    clamped-clamped beam's: no curvature within a clamped length, curvature at mid-span;
    a crack lowers a mode by the modal strain energy at its section times its compliance
    (Dimarogonas, Eng. Fract. Mech. 55 (1996) 831, the local-flexibility model).  So the
    crack mid-pad moves it less than half as much as mid-span (the rim under the pad is
    held on its outer face only, so not nothing)."""
    from hubvib.design.presets import preset_design
    from hubvib.detection.pad_position import counterpart_tooth, crack_position
    from hubvib.elastic.options import ElasticOptions, study_mesh
    from hubvib.meshing.crack import Crack
    from hubvib.reducer.stages import ring_gear

    design = preset_design("raba118")
    ring = ring_gear(design)
    options = ElasticOptions(mesh=study_mesh(), mounting="clamped", cutoff_factor=2.0)
    on_pad = Crack(0, 0.006)
    between = Crack(counterpart_tooth(ring, on_pad), 0.006)
    assert crack_position(ring, on_pad).on_pad and not crack_position(ring, between).on_pad
    intact = _ring_hz(design, None, options, 0)
    pad = _ring_hz(design, on_pad, options, on_pad.tooth)
    span = _ring_hz(design, between, options, between.tooth)
    drop_pad, drop_span = intact[0] - pad[0], intact[0] - span[0]
    assert drop_span > 0 and drop_pad >= 0, (intact[0], pad[0], span[0])
    assert drop_pad < 0.5 * drop_span, (
        f"fundamental {intact[0]:.1f} Hz: the crack mid-pad lowers it {drop_pad:.1f} Hz, "
        f"mid-span {drop_span:.1f} Hz; clamped-clamped beam: less than half mid-pad")
