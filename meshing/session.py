"""A gmsh session that leaves no global state behind."""
from __future__ import annotations

import contextlib
import itertools
import os
import signal
import threading

_counter = itertools.count()


class MeshingError(RuntimeError):
    """gmsh could not build a mesh; the message names the parameters that failed."""


def _restore_sigpipe() -> None:
    """Put back the dispositions of SIGPIPE, SIGTERM and SIGINT that Python and hubvib set
    (``gmsh.initialize`` resets them at the C level).  SIGPIPE: Python ignores it, so that a
    write to a closed pipe raises BrokenPipeError, where the default kills the whole
    process (exit 141): a test run or a pool whose worker died would vanish without a word.
    SIGTERM, SIGINT: the command's handlers, which end a run with one line and nothing
    left in its out folder.  Python still reports the old handlers, so they are installed
    again as they are; only the main thread may do so."""
    if threading.current_thread() is not threading.main_thread():
        return
    for name in ("SIGPIPE", "SIGTERM", "SIGINT"):
        signum = getattr(signal, name, None)
        handler = None if signum is None else signal.getsignal(signum)
        if handler is not None:
            signal.signal(signum, handler)


@contextlib.contextmanager
def gmsh_model(name: str = "hubvib"):
    """Yield the gmsh module with a fresh, empty model made current.

    Initialises gmsh if needed (without its SIGINT handler, so it works in
    threads and worker processes), uses one thread so meshes are repeatable,
    and removes the model afterwards; gmsh is finalised again only if this
    call initialised it.
    """
    import gmsh

    owner = not gmsh.isInitialized()
    if owner:
        gmsh.initialize(readConfigFiles=False, interruptible=False)
        _restore_sigpipe()
    model = f"{name}-{next(_counter)}"
    try:
        log = bool(os.environ.get("HUBVIB_GMSH_LOG"))  # set to see gmsh's own messages
        gmsh.option.setNumber("General.Terminal", int(log))
        gmsh.option.setNumber("General.Verbosity", 5 if log else 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.option.setNumber("Mesh.MaxNumThreads2D", 1)
        gmsh.option.setNumber("Mesh.MaxNumThreads3D", 1)
        gmsh.model.add(model)
        yield gmsh
    finally:
        with contextlib.suppress(Exception):
            gmsh.model.setCurrent(model)
            gmsh.model.remove()
        if owner:
            gmsh.finalize()


def split_crack(gmsh, dim: int, faces: list[int], open_boundary: list[int]) -> list[int]:
    """Duplicate the nodes of the ``dim`` entities ``faces`` with gmsh's Crack plugin.

    ``open_boundary`` (entities of dimension ``dim - 1``) are where the crack
    meets a free surface: without them the crack stays sealed there.  Returns
    the new entities, the second face (the first keeps the tags ``faces``).
    """
    model = gmsh.model
    crack_group = model.addPhysicalGroup(dim, faces, name="crack")
    open_group = model.addPhysicalGroup(dim - 1, open_boundary, name="crack_open")
    before = {tag for _, tag in model.getEntities(dim)}
    gmsh.plugin.setNumber("Crack", "Dimension", dim)
    gmsh.plugin.setNumber("Crack", "PhysicalGroup", crack_group)
    gmsh.plugin.setNumber("Crack", "OpenBoundaryPhysicalGroup", open_group)
    gmsh.plugin.run("Crack")
    return sorted({tag for _, tag in model.getEntities(dim)} - before)


def grade_towards(gmsh, points: list[int], tip_size: float, size: float) -> None:
    """Background mesh size: ``tip_size`` [m] at the gmsh points ``points`` (crack tips),
    growing linearly to ``size`` [m] over ``(size - tip_size) / 0.3``; the size comes from
    this field alone (triangles by Frontal-Delaunay, gmsh algorithm 6)."""
    field = gmsh.model.mesh.field
    distance = field.add("Distance")
    field.setNumbers(distance, "PointsList", points)
    threshold = field.add("Threshold")
    for name, value in (("InField", distance), ("SizeMin", tip_size), ("SizeMax", size),
                        ("DistMin", tip_size), ("DistMax", (size - tip_size) / 0.3)):
        field.setNumber(threshold, name, value)
    field.setAsBackgroundMesh(threshold)
    for name, value in (("Mesh.MeshSizeExtendFromBoundary", 0), ("Mesh.MeshSizeFromPoints", 0),
                        ("Mesh.MeshSizeFromCurvature", 0), ("Mesh.Algorithm", 6)):
        gmsh.option.setNumber(name, value)
