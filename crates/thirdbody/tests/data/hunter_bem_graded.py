#!/usr/bin/env python3
"""
Supplement to bem_check.py: same BEM (exact piecewise-constant cell kernels, SLS
steady-sliding hereditary integral, active set), but on a GRADED mesh refined
geometrically towards both contact edges, to resolve the leading-edge boundary
layer of width ~ V tau that appears at low speed (where a uniform mesh cannot
locate the edges to the accuracy needed for the offset, which is O(V tau)).
"""
import sys
import numpy as np
from hunter_bem_check import influence, P, R, p0, solve_window, edges_from_p


def graded_nodes(xl, xr, e1, e2, h0, hmin, growth=1.15):
    """nodes on [xl,xr], spacing h0 far away, ~hmin at points e1,e2 (geometric growth)."""
    def side(e, direction, stop):
        pts, x, h = [], e, hmin
        while (x - stop) * direction < 0:
            x = x + direction * h
            pts.append(x)
            h = min(h * growth, h0)
        return pts
    pts = [xl, xr, e1, e2]
    pts += side(e1, -1, xl) + side(e1, +1, 0.5 * (e1 + e2))
    pts += side(e2, +1, xr) + side(e2, -1, 0.5 * (e1 + e2))
    x = np.unique(np.clip(np.array(pts), xl, xr))
    # drop nodes closer than hmin/2 (from merging)
    keep = [x[0]]
    for v in x[1:]:
        if v - keep[-1] > 0.5 * hmin:
            keep.append(v)
    keep[-1] = xr
    return np.array(keep)


def solve_mesh(k, lam, xe, act0):
    xc = 0.5 * (xe[:-1] + xe[1:])
    w = np.diff(xe)
    U = influence(xc, xe, k, lam)
    hh = xc**2 / (2 * R)
    act = act0(xc)
    for it in range(300):
        I = np.where(act)[0]
        n = len(I)
        M = np.zeros((n + 1, n + 1))
        M[:n, :n] = U[np.ix_(I, I)]
        M[:n, n] = -1.0
        M[n, :n] = w[I]
        sol = np.linalg.solve(M, np.concatenate([-hh[I], [P]]))
        p = np.zeros(len(xc))
        p[I] = sol[:n]
        gap = hh - sol[n] + U @ p
        neg = act & (p < 0)
        pen = (~act) & (gap < -1e-14)
        if not neg.any() and not pen.any():
            break
        act = act.copy()
        act[neg] = False
        act[pen] = True
    else:
        raise RuntimeError("active set did not converge")
    return xc, w, p, gap, act


def bem_graded(k, lam, hmin, h0=0.004, passes=4):
    # coarse uniform pass for the edge estimates
    xc, h, p, gap, act, it = solve_window(k, lam, -1.6, 1.6, 640)
    er, ef = edges_from_p(xc, h, p, act)
    m = 4
    for ps in range(passes):   # re-grade around the latest edge estimates
        wdt = ef - er
        xe = graded_nodes(er - 0.05 * wdt, ef + 0.05 * wdt, er, ef, h0, hmin)
        xc, w, p, gap, act = solve_mesh(k, lam, xe, lambda x: (x > er + 0.02 * wdt) & (x < ef - 0.02 * wdt))
        I = np.where(act)[0]
        i0, i1 = I[0], I[-1]
        cf = np.polyfit(xc[i1 - m + 1:i1 + 1], p[i1 - m + 1:i1 + 1]**2, 1)
        cr = np.polyfit(xc[i0:i0 + m], p[i0:i0 + m]**2, 1)
        ef, er = -cf[1] / cf[0], -cr[1] / cr[0]
        # keep the extrapolated edge between the last active and first inactive cell centres
        ef = min(max(ef, xc[i1]), xc[min(i1 + 1, len(xc) - 1)])
        er = max(min(er, xc[i0]), xc[max(i0 - 1, 0)])
    mu = np.sum(p * xc * w) / (P * R)
    return dict(a=(ef - er) / 2, c=(ef + er) / 2, mu=mu, pmax=p.max() / p0, n=len(xc),
                gapmin=gap.min())


def main():
    import hunter_reference as H
    cases = [(3.0, 0.001), (10.0, 0.001), (10.0, 0.01)]
    for k, lam in cases:
        ref = H.solve(k, lam)
        print(f"\n## E_inf/E0 = {k:g}, V tau/a0 = {lam:g}   closed form: half-width {ref['a']:.7f}  "
              f"offset {ref['c']:.7f}  pmax/p0 {ref['pmax']/H.p0:.7f}  muR/a0 {ref['mu']:.8f}")
        print("#   hmin     cells  half-width/a0   offset/a0     pmax/p0     mu R/a0    | rel.diff: a, c, pmax, mu")
        for hmin in (1e-4, 1e-5):
            d = bem_graded(k, lam, hmin)
            rel = [(d['a'] - ref['a']) / ref['a'], (d['c'] - ref['c']) / ref['c'],
                   (d['pmax'] - ref['pmax'] / H.p0) / (ref['pmax'] / H.p0), (d['mu'] - ref['mu']) / ref['mu']]
            print(f"{hmin:8.0e} {d['n']:7d} {d['a']:13.7f} {d['c']:12.7f} {d['pmax']:11.7f} {d['mu']:12.8f}  | "
                  + " ".join(f"{r:+.1e}" for r in rel))
            sys.stdout.flush()


if __name__ == '__main__':
    main()
