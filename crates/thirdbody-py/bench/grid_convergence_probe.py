"""Grid convergence over extreme parameters; prints relative differences.

    python crates/thirdbody-py/bench/grid_convergence_probe.py line|point COARSE FINE [GROUP]

Each case (coatings, layers on a rigid base, Zener bodies, the paper's layer; GROUP
picks one of hertz, coated, rigid, visco, layer) is solved on the automatic window
at COARSE and FINE cells (per axis), and the script prints the relative differences
of the peak pressure, the contact's half-width along x, mu and the approach, the
number of warnings at each grid, and any error. Line contacts: a cylinder R = 1 on
E = 1, nu = 0.3 under Q = 1e-3 per unit length; point contacts: a sphere under
Q = 5e-6. Lengths scale with a0, the substrate's Hertz half-width (radius).
docs/validation.md quotes a run (line 256 2048, point 64 192).
"""
import math
import sys

import thirdbody

POINT = sys.argv[1] == "point"
R, E, NU = 1.0, 1.0, 0.3
Q = 5e-6 if POINT else 1e-3
ESTAR = E / (1 - NU**2)
A0 = (3 * Q * R / (4 * ESTAR)) ** (1 / 3) if POINT else math.sqrt(4 * Q * R / (math.pi * ESTAR))
COARSE, FINE = int(sys.argv[2]), int(sys.argv[3])
only = sys.argv[4] if len(sys.argv) > 4 else ""

def base(cells, body="", extra_loading="", layer=""):
    sub = "[substrate]\nyoung = 1.0\npoisson = 0.3\n" if "[body]" not in body and "[substrate]" not in body else ""
    shape, axes = ("sphere", f"[{cells}, {cells}]") if POINT else ("cylinder", f"{cells}")
    return (f"[slider]\nshape = \"{shape}\"\nradius = {R}\n{sub}{body}\n{layer}\n"
            f"[loading]\nnormal_load = {Q}\n{extra_loading}\n[grid]\ncells = {axes}\n")

def metrics(s):
    hw = 0.5 * (s["contact_x_max"] - s["contact_x_min"])
    return dict(p=s["max_pressure"], hw=hw, mu=s.get("friction_coefficient", 0.0),
                D=s["penetration"], w=len(s.get("warnings", [])))

def run(name, text_of):
    out = {}
    for n in (COARSE, FINE):
        try:
            sol = thirdbody.solve(thirdbody.Case.from_toml(text_of(n)))
            out[n] = metrics(sol.summary)
        except (ValueError, RuntimeError) as e:  # report it and go on
            out[n] = str(e)[:160]
    c, f = out[COARSE], out[FINE]
    if isinstance(c, str) or isinstance(f, str):
        print(f"{name:55s} ERROR coarse={c if isinstance(c,str) else 'ok'} | fine={f if isinstance(f,str) else 'ok'}", flush=True)
        return
    rel = lambda k: abs(c[k] - f[k]) / max(abs(f[k]), 1e-300)
    mu_err = abs(c["mu"] - f["mu"]) / max(abs(f["mu"]), 1e-12)
    worst = max(rel("p"), rel("hw"), rel("D"), mu_err if abs(f["mu"]) > 1e-9 else 0)
    flag = "  <==" if worst > 0.01 else ""
    print(f"{name:55s} p {rel('p'):.1e} hw {rel('hw'):.1e} mu {mu_err:.1e} (mu={f['mu']:.3e}) D {rel('D'):.1e} warn {c['w']}/{f['w']}{flag}", flush=True)

groups = {}
groups["hertz"] = [(f"hertz Q={q:g}", (lambda q: lambda n: base(n).replace(f"normal_load = {Q}", f"normal_load = {q}"))(q)) for q in (1e-9, 1e-6, 1e-3, 1e-1)]
coated = []
for ratio in (1e-3, 1e-2, 0.1, 10, 1e2, 1e3):
    for h in (1e-3, 1e-2, 0.1, 1, 10, 100):
        body = f"[coating]\nyoung = {ratio}\npoisson = 0.3\nthickness = {h * A0}\n"
        coated.append((f"coated E1/E2={ratio:g} h/a0={h:g}", (lambda b: lambda n: base(n, b))(body)))
groups["coated"] = coated
rigid = []
for bond in ("bonded", "frictionless"):
    for nu in (0.3, 0.49, 0.499):
        for h in (0.01, 0.1, 1, 10):
            body = (f"[body]\nbase = \"rigid\"\nbonding = \"{bond}\"\n[[body.layers]]\nyoung = 1.0\n"
                    f"poisson = {nu}\nthickness = {h * A0}\n")
            rigid.append((f"rigid {bond} nu={nu} h/a0={h:g}", (lambda b: lambda n: base(n, b))(body)))
groups["rigid"] = rigid
visco = []
for k in (3, 10, 100, 1000):
    for vt in (1e-4, 1e-2, 1, 1e2, 1e4):
        body = (f"[substrate]\nrheology = \"zener\"\nglassy_modulus = {k}\nrelaxed_modulus = 1.0\n"
                f"relaxation_time = 1.0\npoisson = 0.3\n")
        visco.append((f"zener Eg/E0={k} Vtau/a0={vt:g}", (lambda b, v: lambda n: base(n, b, f"velocity = {v}"))(body, vt * A0)))
groups["visco"] = visco
layer = []
for c0 in (1e-4, 0.02, 1.0):
    for v in (1e-6, 1e-4, 1e-2, 1, 1e2):
        lay = f"[layer]\ncompliance = {c0}\nrelaxation_time = 1.0\n"
        layer.append((f"layer C={c0:g} V={v:g}", (lambda l, v: lambda n: base(n, "", f"velocity = {v}", l))(lay, v)))
groups["layer"] = layer
for g, cases in groups.items():
    if only and g != only:
        continue
    print(f"## {g} (cells {COARSE} vs {FINE}, a0 = {A0:.4g})", flush=True)
    for name, f in cases:
        run(name, f)
