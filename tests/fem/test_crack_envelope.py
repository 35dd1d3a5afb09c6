"""The load envelope of ``hubvib crack-path --load envelope`` ("the load is
the planet's mesh force at the worst position of the mesh cycle (and optionally the
envelope over the cycle)"): the MTS driving force against its closed forms, the mesh
cycle's load positions against the gear pair's geometry, and (slow) the envelope growth
on the Raba ring."""
import json
import math

import numpy as np
import pytest

from hubvib.reducer.stages import gear_body, mesh_force, ring_gear
from hubvib.cli import main
from hubvib.design.presets import raba118
from hubvib.fem.crack_propagation import GrowthOptions
from hubvib.fem.fracture import hoop_stress, mts_angle, mts_driving_force
from hubvib.fem.mesh_cycle import GearPair
from hubvib.meshing.ring_mesh import MeshOptions
from hubvib.studies.lefm_path import crack_path, mesh_cycle_positions, single_contact_radius

RABA = raba118()
COARSE = MeshOptions(size=3e-3, tooth_size=0.8e-3, load_size=0.3e-3)


def test_mts_driving_force_closed_forms():
    """Erdogan & Sih (1963): K_I in pure mode I, 2/sqrt(3) |K_II| in pure mode II (1e-12
    relative); for mixed modes the maximum of the Williams hoop stress over the angle,
    found by a dense independent search (1e-9 relative); 0 for a closed crack."""
    assert mts_driving_force(3.0e6, 0.0) == pytest.approx(3.0e6, rel=1e-12)
    assert mts_driving_force(0.0, 2.0e6) == pytest.approx(2 / math.sqrt(3) * 2.0e6, rel=1e-12)
    assert mts_driving_force(0.0, -2.0e6) == pytest.approx(2 / math.sqrt(3) * 2.0e6, rel=1e-12)
    theta = np.linspace(-math.pi * 0.999, math.pi * 0.999, 2_000_001)
    for k_i, k_ii in ((2.3e6, 0.83e6), (1.0e6, -0.4e6), (0.5e6, 3.0e6)):
        found = float(hoop_stress(theta, k_i, k_ii).max())
        assert mts_driving_force(k_i, k_ii) == pytest.approx(found, rel=1e-9), (k_i, k_ii)
        assert mts_driving_force(k_i, k_ii) == pytest.approx(
            float(hoop_stress(mts_angle(k_i, k_ii), k_i, k_ii)), rel=1e-15)
    assert mts_driving_force(-1.0e6, 0.2e6) == 0.0


def test_mesh_cycle_positions_follow_the_path_of_contact():
    """The positions run over the ring's contact span of the planet-ring mesh; the whole
    mesh force acts over the single-pair zone, (2 - eps_alpha) base pitches long on the
    path of contact (1e-12 m), whose end nearest the ring's tip is the worst position of
    ``crack-path`` (the single-contact radius, 1e-12 m); half of it elsewhere."""
    ring, planet = ring_gear(RABA), gear_body(RABA, "planet")
    pair = GearPair(planet, ring)
    positions = mesh_cycle_positions(RABA)
    force = mesh_force(RABA)
    radii = np.array([p.radius for p in positions])
    assert np.all(np.diff(radii) > 0)
    low, high = pair.radii(np.array(pair.path))[1]
    assert radii[0] == pytest.approx(low, rel=1e-8) and radii[-1] == pytest.approx(high, rel=1e-8)
    full = [p for p in positions if p.force == force]
    assert {p.force for p in positions} == {force, force / 2}
    rolls = [GearPair.roll_length(ring, p.radius) for p in full]
    assert max(rolls) - min(rolls) == pytest.approx(
        (2 - pair.contact_ratio) * pair.base_pitch, abs=1e-12), "single-pair zone length"
    assert full[0].radius == pytest.approx(single_contact_radius(RABA), abs=1e-12)


@pytest.mark.slow
def test_envelope_is_driven_from_the_single_contact_point(tmp_path, capsys):
    """Raba tooth 0, three steps on coarse sizes: of the 11 positions of the mesh cycle the
    single-contact point drives every step (the largest MTS driving force: the whole force
    at the largest bending arm), so the envelope path is the worst-position path: K_I,
    K_II within 1 % of |K| and kink angles within 0.1 deg (a point force on the flank
    against the load patch of the worst-position growth, 5 mm and more from the tip:
    St-Venant).  The command writes the envelope's keys."""
    options = GrowthOptions(step=0.5e-3, mesh=COARSE, max_steps=3)
    worst = crack_path(RABA, options, tooth=0)
    envelope = crack_path(RABA, options, tooth=0, load="envelope")
    hpstc = single_contact_radius(RABA)
    for a, b in zip(worst.growth.steps, envelope.growth.steps):
        assert b.load_radius == pytest.approx(hpstc, abs=1e-12), "driving position"
        scale = math.hypot(a.k_i, a.k_ii)
        assert abs(a.k_i - b.k_i) < 0.01 * scale and abs(a.k_ii - b.k_ii) < 0.01 * scale
        assert abs(math.degrees(a.kink_angle - b.kink_angle)) < 0.1
        assert b.k_eq == pytest.approx(mts_driving_force(b.k_i, b.k_ii), rel=1e-15)
    assert main(["crack-path", "--tooth", "0", "--steps", "1", "--load", "envelope", "--json",
                 "--out", str(tmp_path / "env")]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["load"] == "envelope"
    assert len(data["step_load_radius_m"]) == len(data["k_eq_mpa_sqrt_m"]) == 1
    with pytest.raises(SystemExit) as exit_:
        main(["crack-path", "--load", "average"])
    assert exit_.value.code == 2
    assert "argument --load: invalid choice: 'average'" in capsys.readouterr().err
