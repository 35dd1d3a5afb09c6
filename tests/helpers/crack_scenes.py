"""The crack scenes of the study tests: the fast plane crack scene the FE crack tests run (one
text, with the depths, the workers and, where a test asks, the crack path filled in), and the
default scene with a small detection table for the tests on synthetic FE rows."""
from dataclasses import replace


_FAST = """
[reducer]
preset = "raba118"
[crack]
depths = {depths}{path}
accuracy = "fast"
workers = {workers}
[detection]
samples = 200
map_samples = 30
mount_points = 3
[output]
plots = false
renders = false
"""


def fast_crack_scene(depths, workers: int, path: str | None = None) -> str:
    """The scene text: ``depths`` [m] of the plane crack sweep, ``workers`` FE processes,
    ``path`` the ``[crack]`` path word (``"predicted"``, ``"radial"``) or the default."""
    return _FAST.format(depths=list(depths), workers=workers,
                        path="" if path is None else f'\npath = "{path}"')


def synthetic_scene(apply: str):
    """The default scene (depths 0..21 mm and through the rim, 24.66 mm) with ``apply`` the
    mounting rule (``"series"``, ``"ratio"``), no renders and a small detection table."""
    from hubvib.detection.options import DetectionOptions
    from hubvib.studies.scene import load_scene

    scene = load_scene(None)
    small = DetectionOptions(samples=200, map_samples=30, mount_points=3)
    return replace(scene, study=replace(scene.study, apply=apply), renders=False,
                   tables={"detection": small})
