"""Which optional extras a scene needs, checked before any work (``hubvib run``)."""
from __future__ import annotations

import importlib.util


def missing_extras(scene, study) -> str | None:
    """What the scene (its registered ``study`` kind) needs that is not installed, as an
    error message naming the module and the extra that brings it; ``None`` when nothing
    is missing."""
    needs = [("plots = true", "matplotlib", "report", scene.plots)]
    if study.fe:
        needs += [("[crack] (FE stage)", module, "fem", True)
                  for module in ("gmsh", "skfem")] + [("[crack]", "tqdm", "report", True)]
    needs += [("renders = true", module, "render", scene.renders)
              for module in ("pyvista", "imageio")]
    for what, module, extra, wanted in needs:
        if wanted and importlib.util.find_spec(module) is None:
            return (f"scene asks for {what} but {module} is not installed: "
                    f"pip install 'hubvib[{extra}]'")
    return None
