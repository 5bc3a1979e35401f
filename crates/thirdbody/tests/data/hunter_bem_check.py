#!/usr/bin/env python3
"""
Independent check of hunter_reference.py: 1-D boundary-element solution of the same
plane-strain steady-sliding problem (rigid cylinder, frictionless, SLS half-space).

 * piecewise-constant pressure p_j on N equal cells of a window around the contact
 * unit-modulus surface displacement of a uniform strip load (exact per cell):
       q(x) = -(2/pi) sum_j p_j [F(x-s_j) - F(x-s_{j+1})],  F(d) = d ln|d| - d
 * steady-sliding SLS hereditary integral, done exactly per cell:
       u = q/E1* + (1/E0* - 1/E1*) int_0^inf (1/l) e^{-xi/l} q(x+xi) dxi,  l = V tau_c = k V tau
   with  int_0^inf (1/l) e^{-xi/l} F(d+xi) dxi = F(d) + l ln|d| - l e^{d/l} Ei(-d/l)   [= F + l ln|d| + l e^{d/l} E1(d/l)]
 * collocation at cell centres, contact condition u = delta - x^2/(2R) on the active set,
   load balance sum p_j h = P, active-set iteration (drop p<0, add gap<0).
Units as in hunter_reference.py: E0* = R = a0 = 1, P = pi/4, p0 = 1/2.
"""
import sys
import numpy as np
from scipy.special import expi
from scipy.integrate import quad

E0, R = 1.0, 1.0
P = np.pi / 4
p0 = 2 * P / np.pi


def E1s(y):
    """-e^{y} Ei(-y)  (= e^{y} E1(y) for y>0), stable for all real y != 0."""
    y = np.asarray(y, float)
    out = np.empty_like(y)
    big = np.abs(y) > 50
    ys = y[~big]
    out[~big] = -np.exp(ys) * expi(-ys)
    yb = y[big]
    s = np.zeros_like(yb)
    term = 1.0 / yb
    for m in range(30):
        s += term
        term = -term * (m + 1) / yb
    out[big] = s
    return out


def F(d):
    return d * np.log(np.abs(d)) - d


def Phi(d, l):
    return F(d) + l * np.log(np.abs(d)) + l * E1s(d / l)


def check_phi():
    err = 0
    for l in (0.01, 1.0, 50.0):
        for d in (-3.0, -0.2, 0.05, 1.7):
            f = lambda xi: np.exp(-xi / l) / l * F(d + xi)
            pts = [-d] if (d < 0 and -d < 60 * l) else None
            val = quad(f, 0, 60 * l, points=pts, limit=400, epsabs=1e-13, epsrel=1e-12)[0]
            err = max(err, abs(val - Phi(np.array([d]), l)[0]) / max(1, abs(val)))
    return err


def influence(xc, xe, k, lam):
    E1 = k * E0
    l = k * lam
    D = xc[:, None] - xe[None, :]
    Fq = F(D)
    Fv = Phi(D, l)
    Kq = -(2 / np.pi) * (Fq[:, :-1] - Fq[:, 1:])
    W = -(2 / np.pi) * (Fv[:, :-1] - Fv[:, 1:])
    return Kq / E1 + (1 / E0 - 1 / E1) * W


def solve_window(k, lam, xl, xr, N, act0=None):
    xe = np.linspace(xl, xr, N + 1)
    xc = 0.5 * (xe[:-1] + xe[1:])
    h = xe[1] - xe[0]
    U = influence(xc, xe, k, lam)
    hh = xc**2 / (2 * R)
    act = (np.abs(xc) < 0.8 * (xr - xl) / 2) if act0 is None else act0(xc)
    for it in range(200):
        I = np.where(act)[0]
        n = len(I)
        M = np.zeros((n + 1, n + 1))
        M[:n, :n] = U[np.ix_(I, I)]
        M[:n, n] = -1.0
        M[n, :n] = h
        rhs = np.concatenate([-hh[I], [P]])
        sol = np.linalg.solve(M, rhs)
        p = np.zeros(N)
        p[I] = sol[:n]
        delta = sol[n]
        gap = hh - delta + U @ p
        new = act.copy()
        neg = act & (p < 0)
        pen = (~act) & (gap < -1e-14)
        if not neg.any() and not pen.any():
            break
        new[neg] = False
        new[pen] = True
        act = new
    else:
        raise RuntimeError("active set did not converge")
    return xc, h, p, gap, act, it


def edges_from_p(xc, h, p, act):
    """Contact edges: extrapolate p^2 (linear in distance near a square-root edge) to zero,
    using the 4 outermost active cells at each end."""
    I = np.where(act)[0]
    i0, i1 = I[0], I[-1]
    m = 4
    xs, ps = xc[i1 - m + 1:i1 + 1], p[i1 - m + 1:i1 + 1]
    cf = np.polyfit(xs, ps**2, 1)
    xf = -cf[1] / cf[0]
    xs, ps = xc[i0:i0 + m], p[i0:i0 + m]
    cr = np.polyfit(xs, ps**2, 1)
    xr_ = -cr[1] / cr[0]
    return xr_, xf


def bem(k, lam, N):
    # pass 1: coarse, wide window
    xc, h, p, gap, act, it = solve_window(k, lam, -1.6, 1.6, 320)
    I = np.where(act)[0]
    lo, hi = xc[I[0]] - h, xc[I[-1]] + h
    w = hi - lo
    # pass 2: window = contact +- 5 %
    xl, xr = lo - 0.05 * w, hi + 0.05 * w
    xc, h, p, gap, act, it = solve_window(k, lam, xl, xr, N,
                                         act0=lambda x: (x > lo + 0.01 * w) & (x < hi - 0.01 * w))
    xrr, xff = edges_from_p(xc, h, p, act)
    mu = np.sum(p * xc) * h / (P * R)
    j = int(np.argmax(p))
    if 0 < j < len(p) - 1:   # parabolic refinement of the peak
        y0, y1, y2 = p[j - 1], p[j], p[j + 1]
        den = y0 - 2 * y1 + y2
        pk = y1 - 0.125 * (y2 - y0)**2 / den if den < 0 else y1
    else:
        pk = p[j]
    return dict(a=(xff - xrr) / 2, c=(xff + xrr) / 2, mu=mu, pmax=pk / p0, it=it,
                gapmin=gap.min(), h=h, ncont=int(act.sum()))


def main():
    print(f"# check of exact cell hereditary kernel against adaptive quadrature: max rel err {check_phi():.2e}")
    import hunter_reference as H
    cases = [(3.0, 0.001), (3.0, 0.01), (3.0, 0.1), (3.0, 1.0), (3.0, 10.0), (3.0, 100.0),
             (10.0, 0.01), (10.0, 0.1), (10.0, 1.0), (10.0, 10.0), (10.0, 100.0)]
    Ns = [400, 800, 1600, 3200]
    if len(sys.argv) > 1 and sys.argv[1] == 'quick':
        Ns = [400, 800]
    keys = ['a', 'c', 'pmax', 'mu']   # same order as the table columns
    worst = {kk: 0.0 for kk in keys}
    for k, lam in cases:
        ref = H.solve(k, lam)
        refd = dict(a=ref['a'], c=ref['c'], mu=ref['mu'], pmax=ref['pmax'] / H.p0)
        print(f"\n## E_inf/E0 = {k:g}, V tau/a0 = {lam:g}")
        print("#     N   cells_in_contact   half-width/a0   offset/a0     pmax/p0      mu R/a0     min gap")
        res = []
        for N in Ns:
            d = bem(k, lam, N)
            res.append(d)
            print(f"{N:7d} {d['ncont']:8d} {d['a']:19.7f} {d['c']:12.7f} {d['pmax']:12.7f} {d['mu']:12.8f} {d['gapmin']:10.1e}")
        # Richardson (assume O(h) error for edges/mu from the last two grids)
        ext = {kk: 2 * res[-1][kk] - res[-2][kk] for kk in keys}
        print("  Richardson(h) " + " ".join(f"{ext[kk]:12.7f}" for kk in keys))
        print("  closed form   " + " ".join(f"{refd[kk]:12.7f}" for kk in keys))
        rel = {kk: (res[-1][kk] - refd[kk]) / refd[kk] for kk in keys}
        relx = {kk: (ext[kk] - refd[kk]) / refd[kk] for kk in keys}
        print("  rel.diff finest N: " + " ".join(f"{kk}={rel[kk]:+.2e}" for kk in keys))
        print("  rel.diff Richardson: " + " ".join(f"{kk}={relx[kk]:+.2e}" for kk in keys))
        for kk in keys:
            worst[kk] = max(worst[kk], abs(rel[kk]))
    print("\n# worst |rel diff| at finest N over all cases: " + " ".join(f"{kk}={worst[kk]:.2e}" for kk in keys))


if __name__ == '__main__':
    main()
