"""``hubvib run [SCENE]``: run a scene file or a shipped scene by name."""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

from hubvib.foundation.output import json_text, output_set


def add_parser(sub) -> None:
    p = sub.add_parser("run", help="run a scene (default: the embedded Raba 118/76 study)")
    p.add_argument("scene", nargs="?", help="scene TOML file, or the name of a shipped scene "
                   "(hubvib scenes lists them)")
    p.add_argument("--out", type=Path, help="output folder (overrides the scene's)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


def _missing_extras(scene, study) -> str | None:
    """What the scene needs that is not installed, as an error message."""
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


def run(args) -> int:
    from hubvib.runtime.cache_check import check_writable
    from hubvib.studies.kinds import study_of
    from hubvib.studies.scene import load_scene

    scene = load_scene(args.scene)
    study = study_of(scene)
    missing = _missing_extras(scene, study)
    if missing:
        print(f"hubvib: error: {missing}", file=sys.stderr)
        return 2
    folder = Path(args.out or scene.folder)
    if study.fe:  # before any work: the FE results must have a place to go
        check_writable("stiffness")
    # the folder is checked and locked before any work; the files go to a stage and
    # move into place together when all are written (printing comes after: a closed
    # stdout must not cost the files)
    with output_set(folder) as staged:
        result = study.run(scene, staged)
    files = [folder / Path(f).relative_to(staged) for f in result.files]
    if args.json:
        print(json_text(study.summary(scene, result, folder, files)))
        return 0
    print("\n".join(study.lines(scene, result, folder)))
    return 0
