"""The same solid ring problem solved by CalculiX (``ccx``, Debian ``calculix-ccx``).

The mesh goes out as an Abaqus/CalculiX input deck (C3D10 or C3D4; numbers
with 13 significant digits, as ccx reads at most 20 characters per field), the supports as ``*BOUNDARY`` on every
node of the ``supports`` surfaces, and the load as ``*CLOAD``: the consistent
nodal forces of our own load vector, so both codes solve the same discrete
problem and their displacements must agree to solver precision.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import time
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from hubvib.fem.elasticity import dof_components
from hubvib.meshing.fe_mesh import FEMesh, GMSH_TO_VTK_TETRA10

#: C3D10 node order is VTK's (edges 12, 23, 31, 14, 24, 34)
ELEMENT = {"tetra10": ("C3D10", GMSH_TO_VTK_TETRA10), "tetra": ("C3D4", slice(None))}


class CalculixError(RuntimeError):
    """ccx is missing or failed; the message says which and shows its output tail."""


def available() -> bool:
    return shutil.which("ccx") is not None


def node_of_dof(mesh: FEMesh, basis) -> tuple[np.ndarray, np.ndarray]:
    """For every DOF of a vector basis on ``mesh``: its mesh node and component."""
    distance, node = cKDTree(mesh.points).query(basis.doflocs.T)
    if distance.max() > 1e-9:
        raise ValueError(f"a DOF sits {distance.max():.1e} m from every mesh node")
    return node, dof_components(basis)


def write_deck(path: Path, mesh: FEMesh, fixed_nodes, forces: np.ndarray, E: float,
               nu: float) -> Path:
    """Input deck: ``forces`` (n_nodes, 3) [N] at the nodes, ``fixed_nodes`` clamped."""
    kind, order = ELEMENT[mesh.cell_type]
    cells = mesh.cells[:, order] + 1
    lines = ["*HEADING", "hubvib ring", "*NODE"]
    lines += [f"{i + 1},{x:.12e},{y:.12e},{z:.12e}"
              for i, (x, y, z) in enumerate(mesh.points.tolist())]
    lines.append(f"*ELEMENT, TYPE={kind}, ELSET=EALL")
    lines += [f"{i + 1}," + ",".join(map(str, row)) for i, row in enumerate(cells.tolist())]
    lines += ["*NSET, NSET=FIXED"] + [f"{n + 1}," for n in np.unique(fixed_nodes)]
    lines += ["*NSET, NSET=EVERY, GENERATE", f"1,{len(mesh.points)},1"]
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E!r},{nu!r}",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
              "*STEP", "*STATIC", "*BOUNDARY", "FIXED,1,3", "*CLOAD"]
    nodes, components = np.nonzero(forces)
    lines += [f"{n + 1},{c + 1},{forces[n, c]:.12e}" for n, c in zip(nodes, components)]
    lines += ["*NODE PRINT, NSET=EVERY", "U", "*END STEP", ""]
    path.write_text("\n".join(lines))
    return path


def run(deck: Path, threads: int = 2) -> tuple[np.ndarray, float]:
    """Run ccx on ``deck`` (``job.inp``); displacements (n_nodes, 3) [m] and wall seconds."""
    if not available():
        raise CalculixError("ccx not found: install Debian's calculix-ccx")
    job = deck.with_suffix("")
    env = dict(os.environ, OMP_NUM_THREADS=str(threads),
               CCX_NPROC_EQUATION_SOLVER=str(threads))
    started = time.perf_counter()
    done = subprocess.run(["ccx", "-i", job.name], cwd=deck.parent, env=env,
                          capture_output=True, text=True)
    seconds = time.perf_counter() - started
    dat = job.with_suffix(".dat")
    if done.returncode != 0 or not dat.exists() or "ERROR" in done.stdout:
        raise CalculixError(f"ccx failed (exit {done.returncode}): {done.stdout[-800:]}")
    rows = [line.split() for line in dat.read_text().splitlines()]
    values = np.array([[float(v) for v in row[1:4]] for row in rows
                       if len(row) == 4 and re.fullmatch(r"\d+", row[0])])
    nodes = np.array([int(row[0]) for row in rows if len(row) == 4 and re.fullmatch(r"\d+", row[0])])
    u = np.zeros((nodes.max(), 3))
    u[nodes - 1] = values
    return u, seconds
