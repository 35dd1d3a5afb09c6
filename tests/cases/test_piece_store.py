"""The intact pieces on disk (hubvib.cases.piece_store): a condensation read back from the
result cache solves as the one computed, and the crack study picks its ring's mesher."""
import numpy as np
import pytest

pytest.importorskip("gmsh")

from hubvib.cases.piece_store import pieces_on_disk  # noqa: E402
from hubvib.cases.runner import case_inputs, mesher_of  # noqa: E402
from hubvib.cases.sweep import CrackSweep  # noqa: E402
from hubvib.design import preset_design  # noqa: E402
from hubvib.fem import substructure  # noqa: E402
from hubvib.fem.material import Material  # noqa: E402
from hubvib.fem.ring_stiffness import ring_model  # noqa: E402
from hubvib.meshing import ring_pieces as pieces_module  # noqa: E402
from hubvib.meshing.crack import Crack  # noqa: E402
from hubvib.meshing.levels import scaled_options  # noqa: E402
from hubvib.meshing.ring_mesh import ring_mesh  # noqa: E402
from hubvib.reducer import raba118  # noqa: E402


def _solve(ring, crack, loads_seed=3):
    pieces = pieces_module.ring_pieces(ring, crack, scaled_options(4.0))
    model = ring_model(ring, pieces.mesh)
    loads = np.random.default_rng(loads_seed).normal(size=(model.ndofs, 2))
    system = substructure.substructured(pieces, model, Material(), ring.gear.face_width)
    try:
        return system.solve(loads).u
    finally:
        system.release()


def _forget():
    pieces_module.piece_mesh.cache_clear()
    substructure._kept.cache_clear()


@pytest.mark.slow
def test_condensations_read_back_solve_as_computed(tmp_path, monkeypatch):
    """Computed here, then written and read back from the cache (no process memory):
    the same displacements to 1e-12 of the largest, and entries on disk."""
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path))
    ring, crack = raba118.ring_gear(), Crack(0, 0.012)
    _forget()
    expected = _solve(ring, crack)
    for _ in range(2):  # the first run writes the entries, the second reads them
        _forget()
        with pieces_on_disk():
            got = _solve(ring, crack)
        assert np.abs(got - expected).max() <= 1e-12 * np.abs(expected).max(), (
            "substructured solve with cached pieces vs computed (1e-12)")
    names = [p.name for p in (tmp_path / "results").iterdir()]
    assert any(n.startswith("ring-piece-mesh-") for n in names), names
    assert any(n.startswith("ring-piece-condensation-") for n in names), names
    _forget()


def test_the_crack_study_substructures_unless_told_not_to():
    design = preset_design("raba118")
    sweep = CrackSweep((0.0, 0.012), design=design)
    crack = Crack(0, 0.012)
    assert mesher_of(sweep, crack) is pieces_module.ring_pieces
    whole = CrackSweep((0.0, 0.012), design=design, substructure=False)
    assert mesher_of(whole, crack) is ring_mesh
    assert case_inputs(sweep, 0.012) != case_inputs(whole, 0.012), (
        "the ring's mesher is part of a case's cache key")
