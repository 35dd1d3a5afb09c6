"""The README's tables of error / size against time (``python -m hubvib.benchmarks.tables``)."""
from __future__ import annotations

import time
from dataclasses import replace


from hubvib.benchmarks.solid import solid_race
from hubvib.reducer import raba118
from hubvib.fem.annulus import exact_k_theta, fe_k_theta
from hubvib.fem.estimate import estimate_ring
from hubvib.fem.material import Material
from hubvib.meshing import measure
from hubvib.meshing.crack import Crack, CrackFront
from hubvib.meshing.levels import SOLID_LEVELS, SOLID_REFERENCE, solid_options
from hubvib.meshing.ring_mesh import MeshOptions, ring_mesh
from hubvib.meshing.ring_mesh_3d import SOLID_OPTIONS, ring_mesh_3d

def mesh_table() -> list[dict]:
    """2D Raba ring meshing time against element count, intact and cracked."""
    ring = raba118.ring_gear()
    rows = []
    for size, tooth in ((4e-3, 1e-3), (2e-3, 0.5e-3), (1e-3, 0.25e-3)):
        for crack in (None, Crack(0, 5e-3)):
            options = MeshOptions(size=size, tooth_size=tooth, tip_size=1e-5)
            started = time.perf_counter()
            mesh = ring_mesh(ring, crack, options)
            rows.append({"case": "cracked, tip 10 um" if crack else "intact",
                         "tooth_size_mm": tooth * 1e3, "elements": mesh.info["elements"],
                         "nodes_p2": mesh.info["nodes"], "seconds": time.perf_counter() - started})
    return rows


def solid_mesh_table() -> list[dict]:
    """3D Raba ring (P2 tetrahedra) meshing time against element count, with and without cracks."""
    ring = raba118.ring_gear()
    cases = (("intact", None, CrackFront()),
             ("through-width crack 6 mm", Crack(0, 6e-3), CrackFront()),
             ("semi-elliptic 6 x 16 mm", Crack(0, 6e-3), CrackFront("semi_elliptic", 0.5, 8e-3)))
    rows = []
    for scale in (2.0, 1.0):  # 1.0: the solid defaults (tooth 2 mm, load 1 mm, tip 0.5 mm)
        for name, crack, front in cases:
            options = replace(SOLID_OPTIONS, **{k: scale * getattr(SOLID_OPTIONS, k) for k in (
                "size", "tooth_size", "tip_size", "load_size")})
            tooth = options.tooth_size
            started = time.perf_counter()
            mesh = ring_mesh_3d(ring, crack, front, options)
            seconds = time.perf_counter() - started
            rows.append({"case": name, "tooth_size_mm": tooth * 1e3,
                         "elements": mesh.info["elements"], "nodes_p2": mesh.info["nodes"],
                         "volume_rel_error": measure.volume(mesh) / mesh.info["exact_volume"] - 1,
                         "straightened": mesh.info["straightened"], "seconds": seconds})
    return rows


def annulus_table() -> list[dict]:
    """Annulus in torsion: relative error of k_theta against the exact value, and time."""
    a, b, t, steel = 0.08, 0.1, 0.01, Material()
    exact = exact_k_theta(a, b, t, steel)
    rows = []
    for order in (1, 2):
        for size in (8e-3, 4e-3, 2e-3, 1e-3):
            started = time.perf_counter()
            k, dofs = fe_k_theta(a, b, t, steel, size, order)
            rows.append({"order": order, "size_mm": size * 1e3, "dofs": dofs,
                         "relative_error": abs(k / exact - 1),
                         "seconds": time.perf_counter() - started})
    return rows


def ring_table() -> list[dict]:
    """c_ru and c_r of the Raba ring, intact and with a 10 mm root crack, on the default
    mesh with its three-level error (``fem.estimate``): the work-conjugate rim
    parts, as ``hubvib stiffness`` prints them."""
    ring = raba118.ring_gear()
    rows = []
    for name, crack in (("intact", None), ("root crack 10 mm", Crack(0, 10e-3))):
        r = estimate_ring(ring, crack, definition="rim")
        rows.append({"case": name, "dofs": r.dofs, "c_ru": r.c_ru,
                     "c_ru_rel_error": r.c_ru_error / r.c_ru,
                     "c_r": r.c_r, "c_r_rel_error": r.c_r_error / r.c_r,
                     "mesh_s": r.seconds_mesh, "fe_s": r.seconds_fe})
    return rows


def solid_table() -> list[dict]:
    """3D c_ru over the solid mesh levels, raced against CalculiX, with the error against
    a finer reference level (Richardson is unreliable here: the levels refine rim, teeth
    and load patches by different factors, and the differences do not shrink
    geometrically)."""
    rows = [dict(level=i, **solid_race(solid_options(*sizes)))
            for i, sizes in enumerate(SOLID_LEVELS)]
    reference = solid_race(solid_options(*SOLID_REFERENCE), calculix=False)
    rows.append(dict(level="reference", **reference))
    for r in rows:
        r["c_ru_rel_error"] = abs(r["c_ru"] / reference["c_ru"] - 1)
    return rows


def _print(title, rows):
    print(f"\n{title}")
    keys = list(rows[0])
    print(" | ".join(keys))
    for row in rows:
        print(" | ".join(f"{row[k]:.3g}" if isinstance(row.get(k), float) else str(row.get(k, ""))
                         for k in keys))


def main():
    _print("Mesh: 2D Raba ring (P2), time vs elements", mesh_table())
    _print("Mesh: 3D Raba ring (P2 tetrahedra), time vs elements", solid_mesh_table())
    _print("Annulus in torsion: error vs time (exact k_theta)", annulus_table())
    _print("Raba ring c_ru (intact), mesh levels", ring_table())
    _print("Raba ring c_ru in 3D (P2 tetrahedra): error vs time, race against CalculiX",
           solid_table())


if __name__ == "__main__":  # pragma: no cover
    main()
