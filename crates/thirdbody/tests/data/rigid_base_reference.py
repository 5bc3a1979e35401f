"""Exact linear-elastic reference for `tests/rigid_base_indentation.rs`.

Problem: a rigid paraboloid z = r^2 / (2 R) (thirdbody's `Slider::Sphere` gap)
pressed without friction into an elastic layer (Young E, Poisson nu, thickness h)
on a rigid base, the layer either bonded to the base or sliding on it without
friction; small strains, contact conditions on the undeformed surface.

Method (the classical Hankel-transform reduction of the axisymmetric problem to a
Fredholm equation of the second kind, Sneddon / Lebedev-Ufliand type):

  * Surface response of the layer to a normal pressure mode J0(xi r):
    w~(xi) = theta K(xi h) p~(xi) / xi, theta = 2 (1 - nu^2) / E, with, for
    t = xi h and kappa = 3 - 4 nu,
      bonded:        K(t) = (2 kappa sinh 2t - 4t) / (2 kappa cosh 2t + 1 + kappa^2 + 4t^2)
      frictionless:  K(t) = (cosh 2t - 1) / (sinh 2t + 2t)      (independent of nu)
    K -> 1 for a thick layer (Boussinesq).  These closed forms are checked below
    against an independent numerical derivation: the plane-strain Navier
    equations for one Fourier mode written as a first-order system in depth for
    (U, W, sigma_xz, sigma_zz), integrated exactly with a matrix exponential and
    given the base's boundary conditions (check 1).  (The axisymmetric and the
    plane Fourier problems share K(xi h).)
  * With p(r) = -(1/r) d/dr int_r^a s phi(s) / sqrt(s^2 - r^2) ds, the mixed
    problem becomes
      phi(s) - (2/pi) int_0^a phi(t) [m(s - t) + m(s + t)] / 2 dt
          = (2 / (pi theta)) (delta - s^2 / R),
      m(x) = (1/h) int_0^inf (1 - K(u)) cos(u x / h) du,
    the force is F = 2 pi int_0^a phi, and the smooth edge (no pressure
    singularity) is phi(a) = 0, which fixes delta(a).  Nystrom with
    Gauss-Legendre nodes on [0, a]; m by composite Gauss-Legendre in u (1 - K
    decays like t^2 e^{-2t}; cut at u = 60).
  * For a target chi = sqrt(R delta) / h the contact radius a is found by
    bisection on delta(a) = delta, and F(delta) follows.

Checks run by this script (it stops with an AssertionError if one fails):
  1. closed-form K against the numerical transfer-matrix K (both bases,
     nu = 0.3, 0.45, 0.49, 0.499; t = 0.01 ... 8): 1e-9;
  2. thick layer (h = 1e3 a): F / F_Hertz - 1 equals the first-order layer term
     (2/pi) I chi with I = int_0^inf (1 - K): 1e-6;
  3. small chi: (f - 1) / chi -> (2/pi) I; and Dimitriadis et al. (2002)
     bonded leading coefficient -2 alpha0 / pi against (2/pi) I (their fit:
     within 1 %);
  4. convergence: n = 24 and 48 nodes and a doubled u-quadrature agree to 1e-9.

Output: one line per case for the Rust test (R = 1, E = 1, h = 0.1,
delta = chi^2 h^2 / R): base, nu, chi, h, delta, F_exact, f_exact = F/F_Hertz(delta),
a_exact / h, and Dimitriadis' f at chi for reference.

Re-run:  python3 crates/thirdbody/tests/data/rigid_base_reference.py
(numpy + scipy; about six minutes on one core, most of it in the bisections).
"""
import numpy as np
from numpy.polynomial.legendre import leggauss
from scipy.linalg import expm


# ---------------------------------------------------------------- layer kernels
def k_closed(t, nu, base):
    t = np.asarray(t, float)
    e2 = np.exp(-2 * t)
    e4 = e2 * e2
    if base == "bonded":
        k = 3 - 4 * nu
        return (k * (1 - e4) - 4 * t * e2) / (k * (1 + e4) + (1 + k * k + 4 * t * t) * e2)
    if base == "frictionless":
        return (1 - e2) ** 2 / (1 - e4 + 4 * t * e2)
    raise ValueError(base)


def k_transfer(t, nu, base):
    """K from the plane-strain Navier equations of one mode, integrated in depth.

    u = U(z) sin(xi x), w = W(z) cos(xi x) (z down, into the layer), shear
    stress T(z) sin(xi x), normal stress S(z) cos(xi x); xi = 1, depth t, E = 1.
    """
    E = 1.0
    mu = E / (2 * (1 + nu))
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    l2m = lam + 2 * mu
    # y = (U, W, T, S); U' = T/mu + W; W' = (S - lam U)/l2m;
    # T' = l2m U + lam W'; S' = -T.
    M = np.array(
        [
            [0.0, 1.0, 1.0 / mu, 0.0],
            [-lam / l2m, 0.0, 0.0, 1.0 / l2m],
            [l2m - lam * lam / l2m, 0.0, 0.0, lam / l2m],
            [0.0, 0.0, -1.0, 0.0],
        ]
    )
    P = expm(M * t)
    # y(0) = (U0, W0, 0, -1): unit pressure, no shear at the surface.
    if base == "bonded":
        rows = [0, 1]  # U(t) = W(t) = 0
    else:
        rows = [1, 2]  # W(t) = 0, T(t) = 0
    A = P[np.ix_(rows, [0, 1])]
    b = -P[np.ix_(rows, [3])][:, 0] * (-1.0)
    U0, W0 = np.linalg.solve(A, b)
    theta = 2 * (1 - nu * nu) / E
    return W0 / theta  # W0 = theta K / xi, xi = 1


# ------------------------------------------------------------ Fredholm solver
def u_quadrature(per_unit=8, cut=60.0):
    edges = np.linspace(0.0, cut, int(cut * 4) + 1)
    xg, wg = leggauss(per_unit * 2)
    nodes = [0.5 * (b - a) * xg + 0.5 * (a + b) for a, b in zip(edges[:-1], edges[1:])]
    weights = [0.5 * (b - a) * wg for a, b in zip(edges[:-1], edges[1:])]
    return np.concatenate(nodes), np.concatenate(weights)


UQ = {1: u_quadrature(8), 2: u_quadrature(16)}


def m_func(x, nu, base, h, uq=1):
    ug, uw = UQ[uq]
    L = 1.0 - k_closed(ug, nu, base)
    x = np.atleast_1d(x)
    return (np.cos(np.outer(x / h, ug)) @ (uw * L)) / h


def delta_force(a, R, nu, base, h, n=32, E=1.0, uq=1):
    """(delta, F) for contact radius a (smooth edge)."""
    theta = 2 * (1 - nu * nu) / E
    s, w = leggauss(n)
    s = 0.5 * a * (s + 1)
    w = 0.5 * a * w
    S, T = np.meshgrid(s, s, indexing="ij")
    kk = 0.5 * (
        m_func((S - T).ravel(), nu, base, h, uq) + m_func((S + T).ravel(), nu, base, h, uq)
    ).reshape(n, n)
    A = np.eye(n) - (2 / np.pi) * kk * w[None, :]
    c = 2 / (np.pi * theta)
    g = s * s / R
    phi1 = np.linalg.solve(A, c * np.ones(n))  # unit delta
    phi2 = np.linalg.solve(A, c * g)  # the profile
    ka = 0.5 * (m_func(a - s, nu, base, h, uq) + m_func(a + s, nu, base, h, uq))
    phi1a = c + (2 / np.pi) * np.sum(ka * w * phi1)
    phi2a = c * a * a / R + (2 / np.pi) * np.sum(ka * w * phi2)
    delta = phi2a / phi1a
    F = 2 * np.pi * np.sum(w * (delta * phi1 - phi2))
    return delta, F


def force_at(delta, R, nu, base, h, n=32, uq=1):
    """(F, a) at the given approach, by bisection on the contact radius."""
    f = lambda a: delta_force(a, R, nu, base, h, n, uq=uq)[0] - delta
    lo = hi = np.sqrt(R * delta)
    while f(lo) > 0:
        lo *= 0.7
    while f(hi) < 0:
        hi *= 1.3
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(mid) > 0:
            hi = mid
        else:
            lo = mid
        if hi - lo < 1e-14 * hi:
            break
    a = 0.5 * (lo + hi)
    return delta_force(a, R, nu, base, h, n, uq=uq)[1], a


def hertz(delta, R, nu, E=1.0):
    return 4 * E * np.sqrt(R) * delta**1.5 / (3 * (1 - nu * nu))


def dimitriadis_coefficients(nu, base):
    """alpha0, beta0 of Dimitriadis et al., Biophys. J. 82 (2002) 2798."""
    if base == "bonded":
        return (
            -(1.2876 - 1.4678 * nu + 1.3442 * nu * nu) / (1 - nu),
            (0.6387 - 1.0277 * nu + 1.5164 * nu * nu) / (1 - nu),
        )
    return -0.347 * (3 - 2 * nu) / (1 - nu), 0.056 * (5 - 2 * nu) / (1 - nu)


def dimitriadis(chi, nu, base):
    a0, b0 = dimitriadis_coefficients(nu, base)
    pi = np.pi
    return (
        1
        - 2 * a0 * chi / pi
        + 4 * a0**2 * chi**2 / pi**2
        - 8 / pi**3 * (a0**3 + 4 * pi**2 * b0 / 15) * chi**3
        + 16 * a0 / pi**4 * (a0**3 + 3 * pi**2 * b0 / 5) * chi**4
    )


def integral_one_minus_k(nu, base):
    ug, uw = UQ[2]
    return np.sum(uw * (1 - k_closed(ug, nu, base)))


BASES = ("bonded", "frictionless")


def checks():
    # 1. closed-form kernels against the transfer matrix
    worst = 0.0
    for base in BASES:
        for nu in (0.3, 0.45, 0.49, 0.499):
            for t in (0.01, 0.1, 0.3, 0.7, 1.0, 2.0, 4.0, 8.0):
                worst = max(worst, abs(k_closed(t, nu, base) - k_transfer(t, nu, base)))
    print(f"# check 1: closed-form K vs transfer matrix, max |diff| = {worst:.1e}")
    assert worst < 1e-9

    R, nu = 1.0, 0.3
    for base in BASES:
        I = integral_one_minus_k(nu, base)
        # 2. thick layer -> Hertz plus the first-order layer term
        h = 1e3
        a = 1.0
        d, F = delta_force(a, R, nu, base, h)
        chi = np.sqrt(R * d) / h
        dev = F / hertz(d, R, nu) - 1
        first = 2 / np.pi * I * chi
        print(f"# check 2 ({base}): h/a = 1e3, F/F_Hertz - 1 = {dev:.4e}, (2/pi) I chi = {first:.4e}")
        assert abs(dev - first) < 1e-6
        # 3. small-chi slope
        h = 1.0
        chi = 0.005
        F, _ = force_at(chi * chi * h * h / R, R, nu, base, h)
        slope = (F / hertz(chi * chi * h * h / R, R, nu) - 1) / chi
        print(f"# check 3 ({base}): (f-1)/chi at chi = 0.005: {slope:.5f}; (2/pi) I = {2 / np.pi * I:.5f}")
        assert abs(slope - 2 / np.pi * I) < 0.01 * 2 / np.pi * I
    for nu in (0.3, 0.45, 0.49, 0.499):
        for base in BASES:
            I = integral_one_minus_k(nu, base)
            a0, _ = dimitriadis_coefficients(nu, base)
            print(
                f"#   {base:12s} nu = {nu}: exact -2 alpha0/pi = (2/pi) I = {2 / np.pi * I:.4f},"
                f" Dimitriadis -2 alpha0/pi = {-2 * a0 / np.pi:.4f}"
            )
            if base == "bonded":
                assert abs(-a0 / I - 1) < 0.01
    # 4. convergence of the discretisation
    for base in BASES:
        h = 0.1
        d = 0.6**2 * h * h
        F1, _ = force_at(d, 1.0, 0.49, base, h, n=24)
        F2, _ = force_at(d, 1.0, 0.49, base, h, n=48)
        F3, _ = force_at(d, 1.0, 0.49, base, h, n=32, uq=2)
        print(f"# check 4 ({base}, nu 0.49, chi 0.6): n 24 / 48 / finer u: {F1:.12e} {F2:.12e} {F3:.12e}")
        assert abs(F1 / F2 - 1) < 1e-9 and abs(F3 / F2 - 1) < 1e-9


def table():
    R, E, h = 1.0, 1.0, 0.1
    cases = [(b, nu) for b in BASES for nu in (0.3, 0.45, 0.49)] + [("bonded", 0.499)]
    print("# base nu chi h delta F_exact f_exact a_exact/h f_dimitriadis")
    for base, nu in cases:
        for chi in (0.2, 0.4, 0.6):
            d = chi * chi * h * h / R
            F, a = force_at(d, R, nu, base, h)
            f = F / hertz(d, R, nu, E)
            print(
                f"{base} {nu} {chi} {h} {d:.6e} {F:.10e} {f:.8f} {a / h:.6f} {dimitriadis(chi, nu, base):.6f}",
                flush=True,
            )


if __name__ == "__main__":
    checks()
    table()
