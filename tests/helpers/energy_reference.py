"""Independent stiffness matrix: polarisation of the paper's potential energy (eq. 8).

``Pi(q)`` is typed straight from the paper (sun bearing term added), with the
arithmetic (float or mpmath) passed in, and ``K_ij = Pi(e_i + e_j) - Pi(e_i) -
Pi(e_j)``, exact for a quadratic form.  Shares no code with ``lumped.network``.
"""
import mpmath as mp


def potential(q, p, sin, cos):
    xs, ys, xc, yc, xr, yr, us, uc, ur = q[:9]
    a_s, a_r = p["alpha_s"], p["alpha_r"]
    energy = (p["c_c"] * (xc**2 + yc**2) + p["c_r"] * (xr**2 + yr**2) + p["c_s"] * (xs**2 + ys**2)
              + p["c_su"] * us**2 + p["c_cu"] * uc**2 + p["c_ru"] * ur**2)
    for i, th in enumerate(p["theta"]):
        tau, eta, u = q[9 + 3 * i: 12 + 3 * i]
        energy += p["c_p"] * ((yc * sin(th) + xc * cos(th) - eta) ** 2
                              + (yc * cos(th) - xc * sin(th) - tau + uc) ** 2)
        energy += p["c_sp"] * (xs * sin(th - a_s) - ys * cos(th - a_s) - us - u
                               + tau * cos(a_s) + eta * sin(a_s)) ** 2
        factor = p["c_rp_factors"][i] if p["c_rp_factors"] else 1
        energy += factor * p["c_rp"] * (xr * sin(th + a_r) - yr * cos(th + a_r) + u - ur
                               + tau * cos(a_r) - eta * sin(a_r)) ** 2
    return energy / 2


def stiffness_by_polarisation(params, number=float, sin=None, cos=None):
    import math

    sin = sin or math.sin
    cos = cos or math.cos
    p = {k: (tuple(number(t) for t in v) if isinstance(v, list) else number(v))
         for k, v in params.to_dict().items()}
    n = 9 + 3 * len(p["theta"])
    zero = number(0)

    def unit(*indices):
        q = [zero] * n
        for i in indices:
            q[i] = q[i] + number(1)
        return q

    diag = [potential(unit(i), p, sin, cos) for i in range(n)]
    K = [[zero] * n for _ in range(n)]
    for i in range(n):
        for j in range(n):
            K[i][j] = 2 * diag[i] if i == j else potential(unit(i, j), p, sin, cos) - diag[i] - diag[j]
    return K


def mp_frequencies(params, dps=50):
    """Natural frequencies [rad/s] from the polarised energy in ``dps`` digits."""
    from hubvib.lumped.network import mass_diagonal

    with mp.workdps(dps):
        K = stiffness_by_polarisation(params, mp.mpf, mp.sin, mp.cos)
        mass = [mp.mpf(float(m)) for m in mass_diagonal(params)]
        n = len(mass)
        A = mp.matrix(n, n)
        for i in range(n):
            for j in range(n):
                A[i, j] = K[i][j] / mp.sqrt(mass[i] * mass[j])
        values = mp.eigsy(A, eigvals_only=True)
        return sorted(float(mp.sqrt(max(v, 0))) for v in values)
