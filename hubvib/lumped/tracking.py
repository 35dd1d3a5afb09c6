"""Follow modes from one parameter set to the next by their shapes (MAC)."""
from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment

from .modes import mac
from .spectrum import Spectrum


def match(previous: Spectrum, current: Spectrum) -> tuple[np.ndarray, np.ndarray]:
    """Order of ``current``'s modes that continues ``previous``'s, and each pair's MAC."""
    m = mac(previous.shapes, current.shapes, 0.5 * (previous.mass + current.mass))
    rows, cols = linear_sum_assignment(-m)
    order = cols[np.argsort(rows)]
    return order, m[np.arange(m.shape[0]), order]
