"""Indicators by their published definitions (Lebold et al. 2000), each on a synthetic TSA
whose value is known in closed form."""
import math

import numpy as np
import pytest

from hubvib.signal.indicators import (GearOrders, difference_signal, ensemble_variances,
                                      envelope, indicators, regular_signal, residual)

P = 4096
PHI = 2 * math.pi * np.arange(P) / P
#: Raba 118/76: z_r = 64, N = 3; dominant lines 63, 129, 192, ...; harmonics 1-3 for SER
GEAR = GearOrders(64, 3, 3)


def _tsa():
    """Every mesh harmonic in the band (21 of them below order 2047: 63, 129, 192, ...),
    amplitude 1/m, plus first sidebands; what the difference signal must drop."""
    full = GEAR.in_band(P)
    x = np.zeros(P)
    for m, centre in enumerate(full.dominant(), start=1):
        for k, a in ((centre, 1 / m), (centre - 3, 0.2 / m), (centre + 3, 0.2 / m)):
            if k < P // 2:   # lines below the Nyquist order only
                x += a * np.cos(k * PHI + 0.1 * m)
    return x + 0.3 * np.cos(PHI) + 0.1 * np.cos(2 * PHI)


def test_regular_signal_holds_every_mesh_harmonic_in_the_band():
    x = _tsa()
    assert GEAR.in_band(P).harmonics == 32, "harmonics up to order (2047 + 3) // 64"
    np.testing.assert_allclose(regular_signal(x, GEAR), x, atol=1e-12,
                               err_msg="regular = shaft + all mesh components + first "
                                       "sidebands: the synthetic TSA exactly")
    assert np.abs(difference_signal(x, GEAR)).max() < 1e-12


def test_fm4_m6a_m8a_of_one_tone_in_the_difference_signal():
    # d = B cos(k phi): <cos^4> / <cos^2>^2 = 3/2, <cos^6> / <cos^2>^3 = (5/16) / (1/8) = 5/2,
    # <cos^8> / <cos^2>^4 = (35/128) / (1/16) = 35/8 (Wallis integrals), exact on P points
    x = _tsa() + 0.05 * np.cos(40 * PHI)
    v = indicators(x, GEAR, [ensemble_variances(x, GEAR)[0]])
    assert abs(v.fm4 - 1.5) < 1e-9, "FM4 of one tone, closed form 3/2"
    assert abs(v.m6a - 2.5) < 1e-9, "M6A of one tone, closed form 5/2"
    assert abs(v.m8a - 35 / 8) < 1e-9, "M8A of one tone, closed form 35/8"


def test_fm4_of_two_tones_and_energy_ratio():
    # d = A cos(a phi) + B cos(b phi), a, b, a +- b, 3a, 3b distinct and not multiples:
    # <d^4> = 3/8 (A^4 + B^4) + 3/2 A^2 B^2, <d^2> = (A^2 + B^2) / 2
    A, B = 0.05, 0.02
    x = _tsa() + A * np.cos(40 * PHI) + B * np.cos(101 * PHI)
    v = indicators(x, GEAR, [1.0])
    expected = (3 / 8 * (A ** 4 + B ** 4) + 1.5 * A ** 2 * B ** 2) / ((A ** 2 + B ** 2) / 2) ** 2
    assert abs(v.fm4 - expected) < 1e-9, f"FM4 of two tones, closed form {expected:.6f}"
    regular = _tsa()
    er = math.sqrt((A ** 2 + B ** 2) / 2) / np.sqrt(np.mean((regular - regular.mean()) ** 2))
    assert abs(v.er - er) < 1e-9, "ER = RMS(d) / RMS(regular), Lebold et al. 2000"


def test_fm0_of_mesh_lines_in_phase():
    # two mesh components in phase at phi = 0: peak 1 + 0.5, trough found numerically is
    # not needed: a single line gives PP = 2A over A = 2 (Stewart 1977)
    x = np.cos(63 * PHI)
    assert abs(indicators(x, GEAR, [1.0]).fm0 - 2.0) < 1e-12, "FM0 of one mesh line is 2"
    y = np.cos(63 * PHI) + np.cos(129 * PHI) + np.cos(192 * PHI)   # peak 3 at phi = 0
    v = indicators(y, GEAR, [1.0])
    assert abs(v.fm0 - (3 - y.min()) / 3) < 1e-12, "FM0 = PP / sum of mesh amplitudes"


def test_na4_against_the_ensemble_variance():
    # residual r = A_j cos(40 phi): NA4 of record k = (3/8 A_k^4) / (mean_j A_j^2 / 2)^2
    amps = [0.1, 0.2, 0.4]
    mesh = sum(np.cos(k * PHI) / m for m, k in enumerate(GEAR.in_band(P).dominant(), start=1)
               if k < P // 2)   # mesh lines only: the residual drops them, keeps sidebands
    records = [mesh + 0.3 * np.cos(PHI) + a * np.cos(40 * PHI) for a in amps]
    variances = [ensemble_variances(x, GEAR)[0] for x in records]
    np.testing.assert_allclose(variances, [a * a / 2 for a in amps], rtol=1e-9,
                               err_msg="residual variance of a tone A cos: A^2 / 2")
    mean = np.mean([a * a / 2 for a in amps])
    for a, x in zip(amps, records):
        v = indicators(x, GEAR, variances)
        assert abs(v.na4 - 3 / 8 * a ** 4 / mean ** 2) < 1e-9, \
            "NA4 closed form (Zakrajsek et al. 1993 / Lebold et al. 2000)"


def test_nb4_of_an_amplitude_modulated_mesh_line():
    # (1 + m cos(3 phi)) cos(63 phi): lines 60, 63, 66 inside the band 63 +- 32; envelope
    # 1 + m cos(3 phi); NB4 against its own variance = 3/2, against an ensemble with
    # twice the variance = 3/8
    m = 0.4
    x = (1 + m * np.cos(3 * PHI)) * np.cos(63 * PHI)
    s = envelope(x, GEAR)
    np.testing.assert_allclose(s, 1 + m * np.cos(3 * PHI), atol=1e-12,
                               err_msg="Hilbert envelope of an AM line, exact")
    var = ensemble_variances(x, GEAR)[1]
    assert abs(var - m * m / 2) < 1e-12
    assert abs(indicators(x, GEAR, [1.0], [var]).nb4 - 1.5) < 1e-9, "NB4 closed form 3/2"
    assert abs(indicators(x, GEAR, [1.0], [var, 3 * var]).nb4 - 1.5 / 4) < 1e-9


def test_band_limit_drops_orders_above_it():
    x = _tsa() + 0.05 * np.cos(40 * PHI) + 0.05 * np.cos(500 * PHI)
    limited = GearOrders(64, 3, 3, band=210)
    v = indicators(x, limited, [1.0])
    assert abs(v.fm4 - 1.5) < 1e-9, "order 500 lies above the band (210): one tone left"
    assert abs(indicators(x, GEAR, [1.0]).fm4 - 2.25) < 1e-9, \
        "full band: two equal tones, 3/8 * 2 + 3/2 = 2.25"


def test_a_constant_signal_is_refused():
    with pytest.raises(ValueError, match="variance 0"):
        indicators(np.ones(P), GEAR, [1.0])


def test_residual_keeps_sidebands():
    x = np.cos(60 * PHI)
    assert abs(np.var(residual(x, GEAR)) - 0.5) < 1e-12, "sidebands stay in the residual"
    assert np.abs(difference_signal(x, GEAR)).max() < 1e-12, "first sidebands leave d"
