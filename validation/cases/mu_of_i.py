"""The friction law mu(I) of a dense granular flow, from simple shear in a sheared periodic cell.

Set-up (demos/DEMdemo_SimpleShear.cpp, docs/periodic.md): frictional spheres of three sizes
(d = 2 mm, mu = 0.5, e = 0.5, E = 50 MPa) in a Lees-Edwards cell, no walls and no gravity, sheared at
10 1/s at fixed volume fractions from 0.48 to 0.58 (0.50, 0.56, 0.58 with --quick, on smaller cells
over shorter strains). Each fraction gives a steady pressure p and shear stress tau (the stress
inspector, contact plus kinetic part), so mu = tau / p at the inertial number I = rate d / sqrt(p / rho).

References: GDR MiDi (2004), Eur. Phys. J. E 14, 341: in dense flows mu depends on I alone and rises
with it; Jop, Forterre & Pouliquen (2006), Nature 441, 727: mu(I) = mu_s + (mu_2 - mu_s) / (I_0 / I + 1).
Verdicts: mu rises with I at every point; with five points, that form fits them to an rms of 0.02 in mu.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from common import Case, json_lines, run_demo  # noqa: E402

case = Case("mu_of_i", __doc__)
out = run_demo("DEMdemo_SimpleShear", os.path.join(case.args.out, "mu_of_i_run"), *(["--quick"] if case.quick else []))
lines = json_lines(out)
points = sorted((p for p in lines if p.get("case") == "SIMPLE-SHEAR"), key=lambda p: p["inertial_number"])
fit = next((p for p in lines if p.get("fit") == "mu(I)"), None)
I = [p["inertial_number"] for p in points]
mu = [p["mu"] for p in points]

rises = len(points) >= 2 and all(b > a for a, b in zip(mu, mu[1:]))
case.check("mu rises with I (" + ", ".join(f"{m:.3f} at I={i:.3f}" for i, m in zip(I, mu)) + ")", "rising",
           "GDR MiDi (2004), Eur. Phys. J. E 14, 341", "rising" if rises else "not rising", "every point", rises)
if fit and len(points) >= 5:
    case.check(f"mu(I) form fits: mu_s={fit['mu_s']:.3f}, mu_2={fit['mu_2']:.3f}, I_0={fit['I_0']:.3f}; rms",
               0.0, "Jop, Forterre & Pouliquen (2006), Nature 441, 727", round(fit["rms"], 4), "rms <= 0.02",
               fit["rms"] <= 0.02)

import numpy as np  # noqa: E402

fig, ax = case.figure(figsize=(5.5, 4))
ax.plot(I, mu, "o", color="C3", label="engine: steady simple shear")
if fit:
    grid = np.logspace(np.log10(min(I) / 2), np.log10(max(I) * 2), 100)
    ax.plot(grid, fit["mu_s"] + (fit["mu_2"] - fit["mu_s"]) / (fit["I_0"] / grid + 1), "-", color="C0",
            label=f"Jop et al. (2006) form fitted: $\\mu_s$={fit['mu_s']:.3f}, $\\mu_2$={fit['mu_2']:.2f}, "
                  f"$I_0$={fit['I_0']:.2f}")
ax.set_xscale("log")
ax.set_xlabel("inertial number I")
ax.set_ylabel(r"$\mu = \tau / p$")
ax.legend(fontsize=7)
ax.grid(alpha=0.3)
case.save(fig)
case.finish()
