"""Three-sphere stacking: the heaviest top sphere that two spheres with a gap between them hold
(paper s. 3.3.2), against the statics of the stack.

Set-up (the paper's test, after the friction-model study it cites, luningFricModel2021 in its
bibliography): two spheres of m1 = 1 kg and R = 0.15 m lie on a floor with a gap d between them; a
third of the same radius and mass m2 is placed on them, touching both, at rest. Every contact has
mu = 0.2 and rolling resistance Crr (the default model, paper s. 3.1; E = 10 MPa, nu = 0.3, CoR =
0.5; the spheres start at their static overlaps). After 3 s the top sphere has either stayed (its
centre under R/50 lower than at the start) or fallen (more than R/5 lower). The paper raises m2 in
small steps to find the critical mass for each gap and Crr; here one simulation holds every stack,
far apart: for each (d, Crr), m2 climbs a ladder of 3 % steps about the statics' critical mass.

Reference (validation/stacking_theory.py): the stack stands while the contacts' friction forces and
rolling moments, each up to its cap (mu N, Crr R N), can balance both spheres; friction alone gives
no critical mass (the stack stands for every m2 when tan(theta/2) <= mu, theta the top contacts'
angle from the vertical, for none otherwise), rolling resistance gives one: for small Crr the
rolling moments that stop the bottom spheres rolling apart run out, for larger Crr the floor's
friction does. Gaps 5-40 mm (theta 31-35 deg, tan(theta/2) 0.27-0.31, above mu), Crr = 0.02, 0.05
(the rolling moments bind) and 0.1 (the floor's friction binds).

Verdicts: along each ladder the lighter masses stand and the heavier fall, with one change; the
critical mass (the geometric mean of the heaviest standing and lightest falling m2) is within 5 %
of the statics (the ladder's half step is 1.5 %; the rest allows for the load arriving with some
speed rather than quasi-statically).

--quick: gaps 10 and 40 mm, Crr 0.02 and 0.05, 7 masses a ladder (about 20 s on one core).
STACK_DT_FRACTION (the step over the Rayleigh time, default 0.1), STACK_RAMP (the gravity ramp's
length, default 0.5 s), STACK_COR (the restitution coefficient, default 0.5), STACK_ROLLING=spring
(validation/rolling_spring_model.py's rolling moment, which has a static state) and
STACK_ROLLING=caps-total / caps-elastic (validation/elastic_caps_model.py) are the studies of
validation/README.md.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from common import Case, import_deme  # noqa: E402
import stacking_theory as theory  # noqa: E402

case = Case("stacking", __doc__)
deme = import_deme()
import numpy as np  # noqa: E402

R, M1, MU, G, E, NU = 0.15, 1.0, 0.2, 9.81, 1e7, 0.3
COR = float(os.environ.get("STACK_COR", "0.5"))  # the damping study of validation/README.md
STEP = 1.03
# Gravity from 0 to g in 50 steps over 0.5 s (a quasi-static load; STACK_RAMP sets the time), then
# held to 2.5 s after the ramp's end.
RAMP, RAMP_STEPS = float(os.environ.get("STACK_RAMP", "0.5")), 50
T_END = RAMP + 2.5
if case.quick:
    GAPS, CRRS, LADDER = [0.01, 0.04], [0.02, 0.05], range(-3, 4)
else:
    GAPS, CRRS, LADDER = [0.005, 0.01, 0.02, 0.04], [0.02, 0.05, 0.1], range(-8, 5)
SPACING = 1.0  # between stacks (m): far apart


def density(m):
    return m / (4.0 / 3.0 * math.pi * R ** 3)


stacks = []  # (d, Crr, m2, m_theory)
for d in GAPS:
    for crr in CRRS:
        m_th = theory.critical_mass(d, MU, crr, R, M1, G)
        for k in LADDER:
            stacks.append((d, crr, m_th * STEP ** (k + 0.5), m_th))  # rungs straddle m_th

sim = deme.DEMSolver()
sim.SetVerbosity("QUIET")
# STACK_ROLLING=spring: the rolling moment of validation/rolling_spring_model.py (a spring capped at the
# default model's moment, with a static state) in place of the default model's (README says why).
# STACK_ROLLING=caps-total / caps-elastic: the default model as a custom one, its caps from the whole
# normal force or from its elastic part (validation/elastic_caps_model.py; the damping study).
rolling = os.environ.get("STACK_ROLLING", "default")
if rolling == "spring":
    import rolling_spring_model
    rolling_spring_model.use(sim)
elif rolling in ("caps-total", "caps-elastic"):
    import elastic_caps_model
    elastic_caps_model.use(sim, rolling[len("caps-"):])
floor = sim.LoadMaterial({"E": E, "nu": NU, "CoR": COR, "mu": MU, "Crr": 0.0})
mats = {}
for crr in CRRS:
    mats[crr] = sim.LoadMaterial({"E": E, "nu": NU, "CoR": COR, "mu": MU, "Crr": crr})
    sim.SetMaterialPropertyPair("Crr", mats[crr], floor, crr)
side = math.ceil(math.sqrt(len(stacks)))
sim.InstructBoxDomainDimension((-1.0, side * SPACING), (-1.0, side * SPACING), (-0.5, 1.5))
sim.AddBCPlane([0, 0, 0], [0, 0, 1], floor)
bottom_types = {crr: sim.LoadSphereType(M1, R, mats[crr]) for crr in CRRS}
bottoms, tops, top_types, z_top0 = [], [], [], []
for i, (d, crr, m2, _) in enumerate(stacks):
    cx, cy = (i % side) * SPACING, (i // side) * SPACING
    zb = R  # touching, unloaded: gravity is ramped up from zero
    half = R + 0.5 * d
    zt = zb + math.sqrt((2.0 * R) ** 2 - half ** 2)
    bottoms += [[cx - half, cy, zb], [cx + half, cy, zb]]
    tops.append([cx, cy, zt])
    top_types.append(sim.LoadSphereType(m2, R, mats[crr]))
    z_top0.append(zt)
sim.AddClumps([bottom_types[s[1]] for s in stacks for _ in range(2)], bottoms)
top_batch = sim.AddClumps(top_types, tops)
dt = float(os.environ.get("STACK_DT_FRACTION", "0.1")) * deme.RayleighTime(R, density(min(s[2] for s in stacks)), E, NU)
sim.SetInitTimeStep(dt)
sim.SetGravitationalAcceleration([0.0, 0.0, 0.0])
sim.Initialize()
tracker = sim.Track(top_batch)
for k in range(RAMP_STEPS):
    sim.SetGravitationalAcceleration([0.0, 0.0, -G * (k + 1) / RAMP_STEPS])
    sim.DoDynamics(RAMP / RAMP_STEPS)
sim.DoDynamics(T_END - RAMP)
drop = np.asarray(z_top0) - np.asarray(tracker.Positions())[:, 2]
print(f"{len(stacks)} stacks, dt {dt:.2e} s, {T_END} s")

# ---- verdicts, one ladder per (d, Crr) ----
results = []  # (d, crr, m_th, m_measured or None, words)
all_ordered, worst = True, 0.0
for d in GAPS:
    for crr in CRRS:
        idx = [i for i, s in enumerate(stacks) if s[0] == d and s[1] == crr]
        masses = [stacks[i][2] for i in idx]
        m_th = stacks[idx[0]][3]
        states = ["stood" if drop[i] < R / 50 else "fell" if drop[i] > R / 5 else "between" for i in idx]
        fell = [s == "fell" for s in states]
        first = fell.index(True) if True in fell else None
        ordered = ("between" not in states and first is not None and first > 0 and all(fell[first:]))
        m_meas = math.sqrt(masses[first - 1] * masses[first]) if ordered else None
        words = " ".join("S" if s == "stood" else "F" if s == "fell" else "?" for s in states)
        print(f"  d {d * 1e3:4.1f} mm, Crr {crr:.2f}: theory {m_th:.3f} kg; ladder {masses[0]:.3f}..{masses[-1]:.3f}: "
              f"{words}" + (f"; measured {m_meas:.3f} kg ({m_meas / m_th - 1:+.1%})" if ordered else ""))
        all_ordered &= ordered
        if ordered:
            worst = max(worst, abs(m_meas / m_th - 1.0))
        results.append((d, crr, m_th, m_meas, masses, states))

case.check(f"ladders with one change from standing to falling ({len(results)})", len(results),
           "statics (validation/stacking_theory.py)", sum(r[3] is not None for r in results), "all", all_ordered)
case.check("critical top mass, worst relative difference from the statics", 0.0,
           "statics of the stack (validation/stacking_theory.py); paper s. 3.3.2", round(worst, 4), "0.05",
           all_ordered and worst <= 0.05)

# ---- plot: critical mass against the gap, per Crr ----
fig, ax = case.figure(figsize=(6.5, 4.8))
d_line = np.linspace(min(GAPS), max(GAPS), 100)
for k, crr in enumerate(CRRS):
    ax.plot(d_line * 1e3, [theory.critical_mass(x, MU, crr, R, M1, G) for x in d_line], "-", color=f"C{k}",
            label=f"statics, Crr {crr:g}")
    for d, c, m_th, m_meas, masses, states in results:
        if c != crr:
            continue
        for m, s in zip(masses, states):
            ax.plot(d * 1e3, m, "o" if s == "stood" else "x", color=f"C{k}", ms=3, alpha=0.5)
        if m_meas is not None:
            ax.plot(d * 1e3, m_meas, "D", color=f"C{k}", ms=6, mfc="none")
ax.set_yscale("log")
ax.set(xlabel="gap d (mm)", ylabel="top sphere mass m2 (kg)",
       title=f"o stood, x fell after {T_END:g} s; diamonds: measured critical mass (mu {MU:g}, m1 {M1:g} kg)")
ax.title.set_fontsize(8)
ax.legend(fontsize=7)
case.save(fig)
case.finish()
