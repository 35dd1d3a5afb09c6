"""Synthetic FE rows for the detection tests (no FE stage): stiffness falling with depth^2,
with the keys of the FE stage's rows (``tests/detection/test_synthetic_rows.py`` checks
that they look like them)."""
import math

import numpy as np

from hubvib.cases.results import PlaneCase
from hubvib.cases.sweep import CrackSweep
from hubvib.reducer import lumped_preset
from hubvib.detection.carrier import MeshTiming
from hubvib.detection.model import CrackModel

#: FE ring body of Raba 118/76 as the root lands read it formerly (c_ru 1.663e10 N/m
#: +-0.15 %, c_r 3.807e10 N/m +-0.03 %; the rim parts the lumped model uses since are
#: 1.075e10 and 3.764e10); the through-rim crack lowers c_ru to x0.942: synthetic
#: rows, the tests built on them pin their own arithmetic, not the FE values
C_RU, C_R = 1.663e10, 3.807e10
DEEPEST = 0.0246
#: Raba 118/76 ring-planet mesh: z_r = 64, contact ratio 1.416, 3 planets, 150 rpm
TIMING = MeshTiming(64, 1.416, 3, 150 * 2 * math.pi / 60)


#: intact engaged c_rp of the synthetic rows [N/m]: the preset's 3e8, so that the series and
#: the ratio method agree on them (tests of the difference give their own, e.g. the FE 1.48e9)
C_RP_FE = 3.0e8


def synthetic_fe_rows(depths=None, c_ru_drop=0.058, c_r_drop=0.05, c_rp_drop=0.1,
                      c_ru_error=2.5e7, c_r_error=1e7, c_rp_error=1e-3, body_scale=1.0,
                      c_rp_fe=C_RP_FE):
    """Rows with the keys of ``crack_sweep.fe_case``: stiffness falling with depth^2."""
    depths = np.linspace(0, DEEPEST, 9) if depths is None else np.asarray(depths)
    x = depths / depths[-1]
    return [{"depth_m": float(d), "c_ru_N_m": body_scale * C_RU * (1 - c_ru_drop * t * t),
             "c_ru_error_N_m": c_ru_error * body_scale, "c_ru_min_N_m": 0.66 * C_RU * body_scale,
             "c_ru_max_N_m": 1.3 * C_RU * body_scale,
             "c_r_N_m": body_scale * C_R * (1 - c_r_drop * t * t),
             "c_r_error_N_m": c_r_error * body_scale,
             "c_rp_engaged_ratio": 1 - c_rp_drop * t, "c_rp_engaged_ratio_error": c_rp_error * t,
             "c_rp_engaged_min_ratio": 1 - 2 * c_rp_drop * t,
             "c_rp_engaged_intact_N_m": c_rp_fe, "c_rp_engaged_intact_min_N_m": 0.8 * c_rp_fe,
             "c_rp_engaged_intact_window_N_m": c_rp_fe,
             # the root-land readings beside (secondary; the lumped model does not read them)
             "c_ru_root_land_N_m": 1.55 * body_scale * C_RU * (1 - c_ru_drop * t * t),
             "c_ru_root_land_error_N_m": 1.3 * c_ru_error * body_scale,
             "c_r_root_land_N_m": 1.01 * body_scale * C_R * (1 - c_r_drop * t * t),
             "c_r_root_land_error_N_m": c_r_error * body_scale,
             "dofs": 1, "solver": "synthetic",
             "seconds_mesh": 0.0, "seconds_fe": 0.0, "seconds_total": 0.0}
            for d, t in zip(depths, x)]


def synthetic_fe_cases(depths=None, **rows) -> list[PlaneCase]:
    """``synthetic_fe_rows`` typed, as ``cases.runner.crack_cases`` gives its cases."""
    return [PlaneCase.from_dict(row) for row in synthetic_fe_rows(depths, **rows)]


def synthetic_model(apply="series", c_ru_mount=None, c_r_mount=None, **rows) -> CrackModel:
    fe = synthetic_fe_rows(**rows)
    sweep = CrackSweep(tuple(r["depth_m"] for r in fe), apply=apply, c_ru_mount=c_ru_mount,
                       c_r_mount=c_r_mount)
    return CrackModel.from_fe(lumped_preset("raba118"), sweep, fe)
