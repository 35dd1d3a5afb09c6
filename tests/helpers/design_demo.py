"""The demo design of the design tests: a 20/31/82 stage with three planets, as a table
(``DEMO``, SI units), as the text of a design file (``DEMO_TOML``) and edited (``demo``)."""
import json

#: the demo design (a 20/31/82 stage, three planets), SI units
DEMO = {"name": "demo", "n_planets": 3, "module": 2.5e-3, "pressure_angle_deg": 20.0,
        "face_width": 0.030, "sun": {"teeth": 20, "shift": 0.2},
        "planet": {"teeth": 31, "shift": 0.2},
        "ring": {"teeth": 82, "shift": 0.6, "rim_thickness": 0.012},
        "supports": {"count": 6, "arc_deg": 20.0},
        "material": {"E": 210e9, "nu": 0.3, "density": 7850.0}, "load": {"sun_torque": 500.0}}
DEMO_TOML = """[design]
name = "demo"
n_planets = 3
module = 2.5e-3            # m
pressure_angle_deg = 20.0
face_width = 0.030         # m
sun = { teeth = 20, shift = 0.2 }
planet = { teeth = 31, shift = 0.2 }
ring = { teeth = 82, shift = 0.6, rim_thickness = 0.012 }
supports = { count = 6, arc_deg = 20.0 }
material = { E = 210e9, nu = 0.3, density = 7850.0 }
load = { sun_torque = 500.0 }   # N m
"""


def demo(**changes):
    table = json.loads(json.dumps(DEMO))
    for key, value in changes.items():
        if "." in key:
            outer, inner = key.split(".")
            table[outer][inner] = value
        elif value is None:
            table.pop(key)
        else:
            table[key] = value
    return table
