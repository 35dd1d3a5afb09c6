"""The lumped sweep's figures name each curve as the crack study's do (model, mode, intact
frequency, type)."""
from types import SimpleNamespace

import numpy as np

from hubvib.studies.sweep import _frequency_figure, _shift_figure


def test_sweep_curves_are_named_rigid_modes():
    omega = 2 * np.pi * np.array([100.0, 200.0, 200.0])
    shift = SimpleNamespace(omega_base=omega, omega_modified=0.99 * omega, modified_value=2e8,
                            percent=np.array([-1.0, -1.0, -1.0]))
    result = SimpleNamespace(
        base_value=1e8, shifts=[shift],
        baseline=SimpleNamespace(omega=omega, kind=("rotational", "translational",
                                                    "translational")),
        scene=SimpleNamespace(study=SimpleNamespace(parameter="c_ru"), threshold_percent=1.0))
    expected = ["rigid 1: 100.0 Hz rotational",
                "rigid 2 (split pair 2/3, lower): 200.0 Hz translational",
                "rigid 3 (split pair 2/3, upper): 200.0 Hz translational"]
    for figure in (_frequency_figure, _shift_figure):
        ax = figure(result).axes[0]
        assert [line.get_label() for line in ax.get_lines()][:3] == expected
