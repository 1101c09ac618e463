"""Discharge of a flat-bottomed hopper against Beverloo's law.

Set-up (paper s. 6.2.2, test ID 1): a hopper 0.40 m high, 0.20 m wide (x) and 0.04 m deep (y) with a
0.04 x 0.04 m orifice in the middle of its floor (the orifice spans the depth), filled with the
paper's plastic spheres PS (r = 3 mm, rho = 1592 kg/m^3, E = 10 MPa, nu = 0.35, CoR = 0.85) at
mu = 0.40 and Crr = 0.04 (its table of hopper tests), the walls of the same material; 14,058 spheres
dropped from a loose grid settle on a closed orifice (about 0.36 m high), which then opens. Grains
that fall 5 cm below the floor leave the domain and are removed (SetDomainExitPolicy("remove")); the
removed mass over time is the discharge. --quick: 5,000 spheres (about 0.13 m), 2.5 s.

Reference: Beverloo et al. (1961), Chem. Eng. Sci. 15, 260: W = C rho_bulk sqrt(g) (D_h - k d)^(5/2)
with C = 0.58, k = 1.5, d the grain diameter and D_h = 4 A / P the orifice's hydraulic diameter
(0.04 m), rho_bulk the settled bed's bulk density (measured). The steady rate is the slope of the
removed mass between 20 % and 60 % discharged. Verdict: within 20 % of Beverloo's W.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from common import Case, import_deme  # noqa: E402

case = Case("hopper", __doc__)
deme = import_deme()
import numpy as np  # noqa: E402

R, RHO, G = 0.003, 1592.0, 9.81
HALF_X, HALF_Y, ORIFICE_HALF = 0.1, 0.02, 0.02
N = 5000 if case.quick else 14058
MASS = RHO * 4.0 / 3.0 * math.pi * R ** 3

sim = deme.DEMSolver()
sim.SetVerbosity("WARNING")
mat = sim.LoadMaterial({"E": 1e7, "nu": 0.35, "CoR": 0.85, "mu": 0.40, "Crr": 0.04})
sim.InstructBoxDomainDimension((-HALF_X, HALF_X), (-HALF_Y, HALF_Y), (-0.05, 0.56))
sim.SetDomainExitPolicy("remove")
sim.AddBCPlane([-HALF_X, 0, 0], [1, 0, 0], mat)
sim.AddBCPlane([HALF_X, 0, 0], [-1, 0, 0], mat)
sim.AddBCPlane([0, -HALF_Y, 0], [0, 1, 0], mat)
sim.AddBCPlane([0, HALF_Y, 0], [0, -1, 0], mat)
# The floor: two plates of two triangles each, either side of the orifice, facing +z.
v = [[-HALF_X, -HALF_Y, 0], [-ORIFICE_HALF, -HALF_Y, 0], [-ORIFICE_HALF, HALF_Y, 0], [-HALF_X, HALF_Y, 0],
     [ORIFICE_HALF, -HALF_Y, 0], [HALF_X, -HALF_Y, 0], [HALF_X, HALF_Y, 0], [ORIFICE_HALF, HALF_Y, 0]]
f = [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]]
sim.AddWavefrontMeshObject(deme.DEMMeshConnected(v, f, mat))
# The gate under the orifice while the bed settles: a plane of family 2, whose contacts are then
# disabled.
gate = sim.AddExternalObject()
gate.AddPlane([0, 0, 0], [0, 0, 1], mat)
gate.SetFamily(2)
# A loose grid, 30 x 6 per layer, each grain moved by up to 0.3 mm (so that the layers do not stack).
rng = np.random.default_rng(3)
spacing = 0.0066
layer = [(-0.0957 + i * spacing, -0.0165 + j * spacing) for i in range(30) for j in range(6)]
pts = [[x + rng.uniform(-3e-4, 3e-4), y + rng.uniform(-3e-4, 3e-4), 0.0035 + k * spacing]
       for k in range(math.ceil(N / len(layer))) for x, y in layer][:N]
grains = sim.AddClumps(sim.LoadSphereType(MASS, R, mat), pts)
sim.SetInitTimeStep(2e-5)
sim.SetGravitationalAcceleration([0, 0, -G])
sim.Initialize()
sim.DoDynamics(0.45 if case.quick else 0.8)
tr = sim.Track(grains)
z = np.array(tr.Positions())[:, 2]
fill = float(np.max(z) + R)
# Bulk density in a slab away from the floor and the surface.
lo, hi = 0.02, 0.7 * fill
rho_bulk = MASS * np.count_nonzero((z > lo) & (z < hi)) / (2 * HALF_X * 2 * HALF_Y * (hi - lo))
print(f"settled: {N} grains, fill height {fill:.3f} m, bulk density {rho_bulk:.0f} kg/m^3")

sim.DisableContactBetweenFamilies(0, 2)
total = N * MASS
t, m = [0.0], [0.0]
frame, t_end = 0.05, (2.5 if case.quick else 7.5)
while t[-1] < t_end - 1e-9 and sim.GetRemovedMass() < 0.999 * total:
    sim.DoDynamics(frame)
    t.append(t[-1] + frame)
    m.append(sim.GetRemovedMass())
t, frac = np.array(t), np.array(m) / total
window = (frac >= 0.2) & (frac <= 0.6)
d_h = 4 * (2 * ORIFICE_HALF) ** 2 / (4 * 2 * ORIFICE_HALF)
beverloo = 0.58 * rho_bulk * math.sqrt(G) * (d_h - 1.5 * 2 * R) ** 2.5
if np.count_nonzero(window) >= 3:
    rate = float(np.polyfit(t[window], np.array(m)[window], 1)[0])
else:
    rate = float("nan")
print(f"discharged {frac[-1] * 100:.1f} % in {t[-1]:.2f} s; steady rate {rate:.4f} kg/s, Beverloo {beverloo:.4f} kg/s")
case.check("steady mass flow rate, 20-60 % discharged (kg/s)", round(beverloo, 4),
           "Beverloo et al. (1961), C = 0.58, k = 1.5, D_h = 0.04 m, measured bulk density", round(rate, 4), "20 %",
           math.isfinite(rate) and abs(rate - beverloo) <= 0.2 * beverloo)

fig, (a1, a2) = case.figure(1, 2, figsize=(10, 4))
a1.plot(t, frac, "-", color="C0", label="engine: PS spheres (test ID 1)")
if math.isfinite(rate):
    t0 = t[window][0] - frac[window][0] * total / rate
    a1.plot(t, np.clip((t - t0) * beverloo / total, 0, 1), "--", color="k", label="Beverloo's rate")
a1.set(xlabel="time since the orifice opened (s)", ylabel="discharged mass fraction", title="discharge")
a1.legend(fontsize=7)
a2.plot(t[1:], np.diff(m) / frame, "-", color="C0", label="engine: removed mass per frame / frame")
a2.axhline(beverloo, color="k", ls="--", label=f"Beverloo: {beverloo:.3f} kg/s")
if math.isfinite(rate):
    a2.axhline(rate, color="C3", ls=":", label=f"engine, 20-60 %: {rate:.3f} kg/s")
a2.set(xlabel="time (s)", ylabel="mass flow rate (kg/s)", title="flow rate")
a2.legend(fontsize=7)
case.save(fig)
case.finish()
