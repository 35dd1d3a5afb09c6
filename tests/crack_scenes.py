"""The fast plane crack scene the FE crack tests run: one text, with the depths, the
workers and, where a test asks, the crack path filled in."""

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
