"""The intact tooth curves of an FE stage, computed once and shared on disk by its workers."""
import numpy as np
import pytest

from hubvib.reducer.stages import gear_body, material, ring_gear
from hubvib.design import preset_design
from hubvib.fem.tooth_stiffness import ToothCurve
from hubvib.meshing.levels import scaled_options
from hubvib.runtime.tooth_curves import shared_intact_curve


@pytest.fixture
def parts(tmp_path, monkeypatch):
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path))
    design = preset_design("raba118")
    return (ring_gear(design), gear_body(design, "planet"), material(design),
            scaled_options(1.0))


def test_a_curve_computed_once_reads_back_with_every_digit(parts):
    ring, planet, steel, options = parts
    # digits that a decimal round trip with fewer than 17 significant figures would lose
    curve = ToothCurve(np.array([0.101, 0.1023456789012345]),
                       np.array([1.2345678901234567e-9, 3.3333333333333335e-9]), 1234)
    calls = []

    def compute():
        calls.append(1)
        return curve

    first = shared_intact_curve(compute, ring, (0.1, 0.11), steel, options, 0)
    assert first is curve and len(calls) == 1

    def never():
        raise AssertionError("the stored curve must be read, not computed again")

    again = shared_intact_curve(never, ring, (0.1, 0.11), steel, options, 0)
    np.testing.assert_array_equal(again.radii, curve.radii, err_msg="radii: exact round trip")
    np.testing.assert_array_equal(again.compliance, curve.compliance,
                                  err_msg="compliance: exact round trip")
    assert again.dofs == 1234
    # another body, tooth or mesh level is another curve
    for args in ((planet, (0.1, 0.11), steel, options, 0), (ring, (0.1, 0.11), steel, options, 5),
                 (ring, (0.1, 0.11), steel, scaled_options(2.0), 0)):
        shared_intact_curve(compute, *args)
    assert len(calls) == 4, "each different input computed once"


def test_a_damaged_entry_is_computed_again(parts, tmp_path):
    ring, _, steel, options = parts
    curve = ToothCurve(np.array([0.1, 0.2]), np.array([1e-9, 2e-9]), 10)
    shared_intact_curve(lambda: curve, ring, (0.1, 0.2), steel, options, 0)
    [entry] = (tmp_path / "stiffness" / "tooth-curves").glob("*.json")
    entry.write_text(entry.read_text().replace("1e-09", "5e-09"))
    calls = []

    def compute():
        calls.append(1)
        return curve

    out = shared_intact_curve(compute, ring, (0.1, 0.2), steel, options, 0)
    assert calls == [1] and out is curve, "a checksum mismatch recomputes the curve"


@pytest.mark.slow
def test_the_intact_case_measures_the_intact_ring_curve_to_the_last_digit(parts):
    """The intact crack case's own factorisation gives the ring's intact tooth curve
    (``crack_level(..., intact_tooth=...)``): the same floats as ``fe_curve`` on a mesh of
    its own (exact: same mesh, model, factorisation and load columns), so the FE stage
    offers it to the other cases instead of meshing the intact ring once more."""
    from hubvib.fem.crack_level import crack_level
    from hubvib.fem.mesh_cycle import GearPair
    from hubvib.fem.tooth_stiffness import contact_radii, fe_curve
    from hubvib.meshing.ring_mesh import ring_mesh

    ring, planet, steel, _ = parts
    options = scaled_options(4.0)  # coarse: the identity does not depend on the size
    span = contact_radii(ring, [GearPair(planet, ring)])
    level = crack_level(ring, planet, None, ring_mesh(ring, None, options), options, steel,
                        intact_tooth=0)
    alone = fe_curve(ring, span, steel, options, tooth=0)
    np.testing.assert_array_equal(level.intact_tooth.radii, alone.radii)
    np.testing.assert_array_equal(level.intact_tooth.compliance, alone.compliance,
                                  err_msg="intact case's factorisation vs fe_curve: exact")
    assert level.intact_tooth.dofs == alone.dofs


def test_an_offered_curve_is_stored_and_never_computed(parts):
    """``offer_intact_curve`` hands the curve to the FE stage's store: the next process
    reads it instead of computing it."""
    from hubvib.fem import tooth_stiffness

    ring, _, steel, options = parts
    curve = ToothCurve(np.array([0.101, 0.102]), np.array([1e-9, 2e-9]), 99)
    tooth_stiffness.set_intact_store(shared_intact_curve)
    try:
        tooth_stiffness.offer_intact_curve(ring, (0.1, 0.11), steel, options, 3, curve)
    finally:
        tooth_stiffness.set_intact_store(None)
        tooth_stiffness._OFFERED.clear()

    def never():
        raise AssertionError("an offered curve must be read from the store")

    again = shared_intact_curve(never, ring, (0.1, 0.11), steel, options, 3)
    np.testing.assert_array_equal(again.compliance, curve.compliance)
    assert again.dofs == 99
