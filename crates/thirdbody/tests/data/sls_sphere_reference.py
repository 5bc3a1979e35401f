#!/usr/bin/env python3
"""
Independent reference: steady frictionless sliding of a rigid paraboloid
h = r^2/(2R) over a standard-linear-solid (Zener) viscoelastic half-space.

Material (constant Poisson ratio nu, so every modulus below is the plane-strain
one E* = E/(1-nu^2)):
   relaxation modulus  E(t) = E0 + (Einf - E0) exp(-t/tau)   (tau = relaxation time)
   creep compliance    J(t) = 1/Einf + (1/E0 - 1/Einf)(1 - exp(-t/tau_c)),
                       tau_c = tau*Einf/E0  (retardation time)
Steady state, indenter moving in +x at speed V (material flows in -x in the
indenter frame). With q = Boussinesq(p) for a unit modulus:
   u(x) = q(x)/Einf + (1/E0-1/Einf) int_0^inf (1/l) exp(-xi/l) q(x+xi,y) dxi,  l = V tau_c
Units: E0* = 1, R = 1, load W chosen so the relaxed Hertz radius a0 = 1
(W = 4 E0* a0^3/(3R)).  Output: mu*R/a0 vs zeta = V tau / a0.
Discretisation: piecewise-constant pressure on an NxN grid over [-L,L]^2,
exact Love kernel, zero-padded FFT (linear convolution), memory integral by
product integration of exp() x piecewise-linear kernel + Gauss-Laguerre tail
(point-force far field). Contact: active set + GMRES (kernel is non-symmetric).
"""
import numpy as np, sys, time
from scipy.sparse.linalg import gmres, LinearOperator

def Phi(s, t):
    with np.errstate(divide='ignore', invalid='ignore'):
        a = np.where(s != 0, s*np.arcsinh(t/np.abs(np.where(s != 0, s, 1.0))), 0.0)
        b = np.where(t != 0, t*np.arcsinh(s/np.abs(np.where(t != 0, t, 1.0))), 0.0)
    return a + b

def love(X, Y, dx):
    """surface deflection at (X,Y) from unit pressure on a dx*dx square at origin, E*=1"""
    h = dx/2
    return (Phi(X+h, Y+h) - Phi(X+h, Y-h) - Phi(X-h, Y+h) + Phi(X-h, Y-h))/np.pi

def build_kernel(N, dx, k, ell, sub=8, nlag=80):
    """kernel K(X,Y) on offsets -(N-1)..(N-1) (stored in 2N periodic layout)."""
    E0, Einf = 1.0, k
    dJ = 1/E0 - 1/Einf
    off = np.arange(-(N-1), N)*dx                       # 2N-1 offsets
    Xo, Yo = np.meshgrid(off, off, indexing='ij')
    G = love(Xo, Yo, dx)
    if ell <= 0:      # zeta=0 : relaxed elastic
        Kv = G
    else:
        h = dx/sub
        xi1 = 2*N*dx
        nxi = int(round(xi1/h))
        xi = np.arange(nxi+1)*h
        # product-integration weights for int_0^xi1 (1/l)e^{-xi/l} f(xi) dxi, f piecewise linear
        w = np.zeros(nxi+1)
        r = h/ell
        e0 = np.exp(-xi[:-1]/ell); e1 = np.exp(-xi[1:]/ell)
        # on [xi_j, xi_j+1]: int (1/l)e^{-s/l} (f_j (1-t) + f_j+1 t), t=(s-xi_j)/h
        if r > 1e-4:
            A = e0*( (1 - np.exp(-r)) )            # int (1/l) e^{-s/l} ds over the cell
            B = e0*( (1 - np.exp(-r)*(1 + r))/r )  # int (1/l)e^{-s/l} t ds
        else:
            A = e0*(r - r*r/2); B = e0*(r/2 - r*r/3)
        w[:-1] += A - B; w[1:] += B
        # fine lattice of X values: X_i + xi, X_i = m*dx, xi = j*h -> index m*sub + j
        mlo = -(N-1)*sub; mhi = (N-1)*sub + nxi
        Xf = np.arange(mlo, mhi+1)*h
        Kv = np.zeros_like(G)
        for jy, Y in enumerate(off):
            Gf = love(Xf, np.full_like(Xf, Y), dx)
            # Kv(X_m) = sum_j w_j Gf[(m*sub - mlo) + j]
            c = np.correlate(Gf, w, mode='valid')    # c[i] = sum_j w_j Gf[i+j]
            Kv[:, jy] = c[(np.arange(-(N-1), N)*sub - mlo)]
        # tail xi > xi1, point-force far field, Gauss-Laguerre in t=(xi-xi1)/l
        tl, wl = np.polynomial.laguerre.laggauss(nlag)
        if xi1/ell < 700:
            fac = np.exp(-xi1/ell)*dx*dx/np.pi
            tail = np.zeros_like(G)
            for t_, w_ in zip(tl, wl):
                tail += w_/np.sqrt((Xo + xi1 + ell*t_)**2 + Yo**2)
            Kv += fac*tail
    K = G/Einf + dJ*Kv
    # embed in 2N x 2N periodic layout for linear convolution
    Kp = np.zeros((2*N, 2*N))
    idx = np.r_[np.arange(0, N), np.arange(-(N-1), 0)]
    Kp[np.ix_(idx % (2*N), idx % (2*N))] = K[np.ix_(idx + (N-1), idx + (N-1))]
    return np.fft.rfft2(Kp)

def solve(N=128, L=1.6, k=10.0, zeta=1.0, R=1.0, W=None, tol=1e-10, verbose=False):
    dx = 2*L/N
    x = -L + (np.arange(N)+0.5)*dx
    X, Y = np.meshgrid(x, x, indexing='ij')
    if W is None: W = 4.0/(3*R)                 # a0 = 1 with E0*=1
    tau = 1.0
    V = zeta/tau                                 # a0 = 1
    ell = V*tau*k                                # V*tau_c
    Kh = build_kernel(N, dx, k, ell)
    hgt = (X**2 + Y**2)/(2*R)
    def conv(p):
        P = np.zeros((2*N, 2*N)); P[:N, :N] = p
        return np.fft.irfft2(np.fft.rfft2(P)*Kh, s=(2*N, 2*N))[:N, :N]
    # initial guess: Hertz with effective modulus
    A = hgt < 1.0
    p = np.zeros((N, N)); delta = 0.5
    for it in range(200):
        ia = np.flatnonzero(A.ravel()); na = ia.size
        def mv(v):
            pp = np.zeros(N*N); pp[ia] = v[:na]
            u = conv(pp.reshape(N, N)).ravel()
            return np.r_[u[ia] - v[na], pp.sum()*dx*dx/W]
        op = LinearOperator((na+1, na+1), matvec=mv)
        rhs = np.r_[-hgt.ravel()[ia], 1.0]
        x0 = np.r_[p.ravel()[ia], delta]
        sol, info = gmres(op, rhs, x0=x0, rtol=tol, restart=200, maxiter=2000)
        pf = np.zeros(N*N); pf[ia] = sol[:na]; delta = sol[na]
        p = pf.reshape(N, N)
        u = conv(p); g = hgt - delta + u
        neg = A & (p < 0)
        pen = (~A) & (g < -1e-12*max(1, abs(delta)))
        if verbose: print(it, na, neg.sum(), pen.sum(), info, delta)
        if not neg.any() and not pen.any(): break
        if neg.any():
            A = A & ~neg
            p[neg] = 0
        else:
            A = A | pen
    F = (p*X/R).sum()*dx*dx
    mu = F/W
    area = A.sum()*dx*dx
    xc = (p*X).sum()/p.sum()
    xs = X[A]
    return dict(mu=mu, delta=delta, area=area, a_eq=np.sqrt(area/np.pi), pmax=p.max(),
                xfront=xs.max()+dx/2, xrear=xs.min()-dx/2, xc=xc, iters=it, p=p, x=x)

if __name__ == '__main__':
    k = float(sys.argv[1]) if len(sys.argv) > 1 else 10.0
    N = int(sys.argv[2]) if len(sys.argv) > 2 else 128
    zetas = [float(z) for z in sys.argv[3].split(',')] if len(sys.argv) > 3 else \
        [0.0, 0.01, 0.03, 0.1, 0.2, 0.3, 0.5, 1, 2, 3, 5, 10, 30, 100]
    print(f"# k=Einf/E0={k} N={N}")
    print("# zeta=V*tau/a0  mu*R/a0  delta*R/a0^2  a_eq/a0  pmax/E0*  x_front/a0  x_rear/a0  iters  sec")
    for z in zetas:
        t0 = time.time()
        r = solve(N=N, k=k, zeta=z)
        print(f"{z:8.3f} {r['mu']:.5f} {r['delta']:.5f} {r['a_eq']:.4f} {r['pmax']:.4f} "
              f"{r['xfront']:.4f} {r['xrear']:.4f} {r['iters']:3d} {time.time()-t0:.1f}", flush=True)
