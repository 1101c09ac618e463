"""Single impacts against theory: the contact benchmarks of Chung & Ooi (2011), Granular Matter 13, 643.

The engine's Hertz-Mindlin model (docs/physics.md) in the eight set-ups of Chung & Ooi's benchmark,
with materials of our choosing (spheres of R = 10 mm, E = 70 GPa, nu = 0.33, rho = 2700 kg/m^3, an
aluminium alloy's values; walls of the same material; no gravity), each compared with the theory it has:

 1. two identical spheres meeting head-on, elastic (CoR = 1, mu = 0): contact time, largest overlap
    and largest force against Hertz theory (Johnson, Contact Mechanics, 1985, s. 11.1):
    delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5), F_max = 4/3 E* sqrt(R*) delta_max^(3/2),
    t_c = 2.9432 delta_max / v;  within 2 %;
 2. a sphere hitting a wall, elastic, at 0.2 to 5 m/s: the contact time against Hertz (t_c ~ v^(-1/5)),
    and the rebound speed equal to the impact speed, within 2 %;
 3. a sphere hitting a wall with CoR 0.3 to 0.9 at 0.2 to 5 m/s: the restitution within 5 % of CoR
    (the damping is derived from CoR so that it is; paper s. 3.1) and independent of the speed within
    1 % (Tsuji et al. 1992: damping ~ sqrt(m k_n) keeps it so for Hertz contacts);
 4. oblique impacts on a wall at 3.9 m/s, incidence 5 to 85 degrees from the normal (mu = 0.1, CoR = 1);
 5. oblique impacts at a normal speed of 5 m/s and tangential speeds 0.5 to 10 m/s;
 6. impacts at a normal speed of 5 m/s, no tangential speed, and spins of 10 to 1000 rad/s;
 7. two identical spheres meeting at a normal speed of 5 m/s, both spinning at w about one axis
    (their surfaces slide past each other at 2 w R);
 8. a sphere of R and one of 2 R meeting likewise, the small one spinning.
For 4 to 8 the reference is rigid-body impact theory with Coulomb friction (Maw, Barber & Fawcett
1976; Chung & Ooi's analytical lines): while the contact point slides throughout, the tangential
impulse is mu (1 + e) m* v_n and the final velocities and spins follow; the slip stops (the ball
rolls off) where the initial slip is below 7/2 mu (1 + e) v_n (for two spheres, that times m* (1/m_A +
1/m_B)). Verdicts on the final tangential speed and spin where the contact slides throughout, within
2 % of the initial tangential momentum scale; below the sliding limit Mindlin's tangential compliance
makes the answer differ from the rigid one (Maw et al.), so those points are plotted, not judged.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from common import Case, import_deme  # noqa: E402

case = Case("impacts", __doc__)
deme = import_deme()
import numpy as np  # noqa: E402

R, E, NU, RHO = 0.01, 7e10, 0.33, 2700.0
HERTZ = "Hertz theory, Johnson (1985) s. 11.1"
RIGID = "rigid-body impact with Coulomb friction (Maw, Barber & Fawcett 1976; Chung & Ooi 2011)"


def mass(r):
    return RHO * 4.0 / 3.0 * math.pi * r ** 3


def e_star():  # same material on both sides
    return 1.0 / (2.0 * (1.0 - NU ** 2) / E)


def hertz(m_eff, r_eff, v):
    """Largest overlap, largest force and contact time of an elastic Hertz impact at speed v."""
    es = e_star()
    d = (15.0 * m_eff * v * v / (16.0 * es * math.sqrt(r_eff))) ** 0.4
    return d, 4.0 / 3.0 * es * math.sqrt(r_eff) * d ** 1.5, 2.9432 * d / v


def impact(bodies, cor, mu, wall, v_n, record=False):
    """Runs one impact. bodies: list of (radius, position, velocity, spin); with `wall` a plane at z = 0
    (normal +z) is the partner of the single body. Returns each body's final velocity and spin, and
    with `record` the contact time, largest force and largest overlap (first body)."""
    sim = deme.DEMSolver()
    sim.SetVerbosity("QUIET")
    mat = sim.LoadMaterial({"E": E, "nu": NU, "CoR": cor, "mu": mu, "Crr": 0.0})
    sim.InstructBoxDomainDimension((-0.5, 0.5), (-0.5, 0.5), (-0.5, 0.5))
    if wall:
        sim.AddBCPlane([0, 0, 0], [0, 0, 1], mat)
    batches = [sim.AddClumps(sim.LoadSphereType(mass(r), r, mat), [p]) for r, p, _, _ in bodies]
    r_eff = bodies[0][0] if wall else bodies[0][0] * bodies[1][0] / (bodies[0][0] + bodies[1][0])
    m_a = mass(bodies[0][0])
    m_eff = m_a if wall else m_a * mass(bodies[1][0]) / (m_a + mass(bodies[1][0]))
    tc = hertz(m_eff, r_eff, v_n)[2]
    dt = tc / 400.0
    sim.SetInitTimeStep(dt)
    sim.SetGravitationalAcceleration([0, 0, 0])
    sim.Initialize()
    trackers = [sim.Track(b) for b in batches]
    for tr, (_, _, v, w) in zip(trackers, bodies):
        tr.SetVel(list(v))
        tr.SetAngVel(list(w))
    contact_time, f_max, overlap_max, touched = 0.0, 0.0, 0.0, False
    if record:
        for _ in range(100000):
            sim.DoStepDynamics()
            f = float(np.linalg.norm(trackers[0].ContactForce()))
            if wall:
                overlap = bodies[0][0] - trackers[0].Pos()[2]
            else:
                gap = np.linalg.norm(np.array(trackers[1].Pos()) - np.array(trackers[0].Pos()))
                overlap = bodies[0][0] + bodies[1][0] - gap
            if f > 0.0:
                touched = True
                contact_time += dt
                f_max = max(f_max, f)
                overlap_max = max(overlap_max, overlap)
            elif touched:
                break
    else:
        sim.DoDynamics(40 * dt + 3.0 * tc)
    final = [(np.array(tr.Vel()), np.array(tr.AngVelGlobal())) for tr in trackers]
    return final, contact_time, f_max, overlap_max


def gap_for(v_rel):
    """Two spheres of R start 20 steps' travel apart."""
    return v_rel * 20 * (hertz(mass(R) / 2, R / 2, max(v_rel, 1e-3))[2] / 400.0)


def wall_start(v_n):
    """A sphere of R starts 20 steps' travel above the wall."""
    return R + v_n * 20 * hertz(mass(R), R, v_n)[2] / 400.0


def rigid(m_a, r_a, m_b, r_b, v_n, slip, mu, e):
    """Rigid-body theory: the tangential impulse on A (along the slip's opposite) and whether the
    contact slides throughout. m_b = inf for a wall."""
    inv = 1.0 / m_a + (0.0 if math.isinf(m_b) else 1.0 / m_b)
    jn = (1.0 + e) * v_n / inv
    stick_jt = abs(slip) / (3.5 * inv)  # the impulse that stops the slip (I = 2/5 m r^2 each)
    slides = mu * jn < stick_jt
    return min(mu * jn, stick_jt), slides


results = {}
speeds = [0.2, 1.0, 5.0] if case.quick else [0.2, 0.5, 1.0, 2.0, 5.0]

# 1. Two identical spheres, head-on, elastic.
v = 5.0
g = gap_for(v)
(fa, fb), tcm, fm, dm = impact([(R, [-R - g / 2, 0, 0], [v / 2, 0, 0], [0, 0, 0]),
                                 (R, [R + g / 2, 0, 0], [-v / 2, 0, 0], [0, 0, 0])], 1.0, 0.0, False, v, record=True)
d_th, f_th, t_th = hertz(mass(R) / 2, R / 2, v)
for q, meas, ref in (("test 1: contact time (s)", tcm, t_th), ("test 1: largest overlap (m)", dm, d_th),
                     ("test 1: largest force (N)", fm, f_th)):
    case.check(q, f"{ref:.4g}", HERTZ, f"{meas:.4g}", "2 %", abs(meas - ref) <= 0.02 * ref)
results["t1"] = (tcm, t_th)

# 2. and 3. A sphere on a wall: elastic, then damped.
t2 = []
for v in speeds:
    (f,), tcm, _, _ = impact([(R, [0, 0, wall_start(v)], [0, 0, -v], [0, 0, 0])], 1.0, 0.0, True, v, record=True)
    t2.append((v, tcm, hertz(mass(R), R, v)[2], f[0][2] / v))
ok_t = all(abs(t - th) <= 0.02 * th for _, t, th, _ in t2)
ok_e = all(abs(e - 1.0) <= 0.02 for *_, e in t2)
worst_t = max((t / th for _, t, th, _ in t2), key=lambda ratio: abs(ratio - 1))
case.check("test 2: contact time at " + ", ".join(f"{v:g}" for v, *_ in t2) + " m/s (worst ratio to Hertz)",
           1.0, HERTZ, round(worst_t, 4), "2 % at every speed", ok_t)
case.check("test 2: rebound / impact speed, elastic (worst)", 1.0, "energy conservation",
           round(min(t2, key=lambda x: -abs(x[3] - 1))[3], 4), "2 % at every speed", ok_e)
t3 = {}
for cor in ([0.3, 0.7] if case.quick else [0.3, 0.5, 0.7, 0.9]):
    t3[cor] = []
    for v in speeds:
        (f,), *_ = impact([(R, [0, 0, wall_start(v)], [0, 0, -v], [0, 0, 0])], cor, 0.0, True, v)
        t3[cor].append(f[0][2] / v)
    es = t3[cor]
    case.check(f"test 3: restitution at CoR {cor} (mean over speeds)", cor, "the damping's derivation (paper s. 3.1)",
               round(float(np.mean(es)), 4), "5 %", abs(np.mean(es) - cor) <= 0.05 * cor)
    case.check(f"test 3: restitution's spread over {speeds[0]:g}-{speeds[-1]:g} m/s at CoR {cor}", 0.0,
               "Tsuji, Tanaka & Ishida (1992)", round(float((max(es) - min(es)) / np.mean(es)), 4), "1 %",
               (max(es) - min(es)) <= 0.01 * np.mean(es))

# 4. to 8.: oblique impacts. Each run: initial slip, measured and rigid-theory final tangential speed
# and spin of the first body (all tangential motion along x, spins about y).
MU = 0.1


def oblique_wall(vn, vt, w):
    (f,), *_ = impact([(R, [0, 0, wall_start(vn)], [vt, 0, -vn], [0, w, 0])], 1.0, MU, True, vn)
    slip = vt - w * R  # the contact point's speed along x (contact below the centre)
    jt, slides = rigid(mass(R), R, math.inf, R, vn, slip, MU, 1.0)
    s = math.copysign(1.0, slip)
    return slip, slides, (f[0][0], f[1][1] * R), (vt - s * jt / mass(R), (w + s * 2.5 * jt / (mass(R) * R)) * R)


def oblique_pair(vn, w_a, w_b, r_b):
    # A at the left moving +x (normal), B at the right; tangential direction z, spins about y.
    g = gap_for(vn)
    (fa, fb), *_ = impact([(R, [-R - g / 2, 0, 0], [vn / 2, 0, 0], [0, w_a, 0]),
                           (r_b, [r_b + g / 2, 0, 0], [-vn / 2, 0, 0], [0, w_b, 0])], 1.0, MU, False, vn)
    # Contact point velocity along z on A: v_z + (w x r)_z with r = (R, 0, 0): -w_y R ... (w x r)_z = w_x*0 - w_y*R
    slip = (-w_a * R) - (w_b * r_b)  # A's contact point minus B's (B's r = (-r_b, 0, 0): (w x r)_z = w_y r_b)
    jt, slides = rigid(mass(R), R, mass(r_b), r_b, vn, slip, MU, 1.0)
    s = math.copysign(1.0, slip)
    # On A the tangential impulse is -s jt along z; torque about y: r x F = (R,0,0) x (0,0,-s jt) -> +s jt R along y.
    return slip, slides, (fa[0][2], fa[1][1] * R), (-s * jt / mass(R), (w_a + s * 2.5 * jt / (mass(R) * R)) * R)


def judge(name, runs, scale):
    sliding = [r for r in runs if r[2]]
    if not sliding:  # the set-up must reach the sliding regime, or it tests nothing
        case.check(f"{name}: runs where the contact slides", ">= 1", RIGID, 0, "at least one", False)
        return
    worst = max(max(abs(m - t) for m, t in zip(r[3], r[4])) for r in sliding) / scale
    case.check(f"{name}: final tangential speed and spin x R where the contact slides ({len(sliding)} of {len(runs)} "
               "runs; worst difference / scale)", 0.0, RIGID, round(worst, 4), "2 %", worst <= 0.02)


n = 5 if case.quick else 12
t4 = []
for ang in np.linspace(5, 85, n):
    vn, vt = 3.9 * math.cos(math.radians(ang)), 3.9 * math.sin(math.radians(ang))
    slip, slides, meas, th = oblique_wall(vn, vt, 0.0)
    t4.append((ang, slides, slides, meas, th, vt, vn))
judge("test 4", [(a, None, s, m, t) for a, _, s, m, t, *_ in t4], 3.9)
t5 = []
for vt in np.linspace(0.5, 10, n):
    slip, slides, meas, th = oblique_wall(5.0, vt, 0.0)
    t5.append((vt, None, slides, meas, th))
judge("test 5", t5, 5.0)
t6 = []
for w in np.linspace(10, 1000, n):
    slip, slides, meas, th = oblique_wall(5.0, 0.0, w)
    t6.append((w, None, slides, meas, th))
judge("test 6", t6, 5.0)
t7, t8 = [], []
for w in np.linspace(10, 1000, n):
    t7.append((w, None, *oblique_pair(5.0, w, w, R)[1:]))
    t8.append((w, None, *oblique_pair(5.0, w, 0.0, 2 * R)[1:]))
judge("test 7", t7, 5.0)
judge("test 8", t8, 5.0)

fig, axes = case.figure(2, 3, figsize=(13, 7.5))
ax = axes[0][0]
ax.plot([v for v, *_ in t2], [t for _, t, *_ in t2], "o", color="C3", label="engine")
vv = np.linspace(min(speeds) * 0.8, max(speeds) * 1.2, 50)
ax.plot(vv, [hertz(mass(R), R, x)[2] for x in vv], "-", label="Hertz")
ax.set_xscale("log"), ax.set_yscale("log")
ax.set(xlabel="impact speed (m/s)", ylabel="contact time (s)", title="test 2: sphere on a wall, elastic")
ax.legend(fontsize=7)
ax = axes[0][1]
for cor, es in t3.items():
    ax.plot(speeds, es, "o-", label=f"CoR {cor}")
    ax.axhline(cor, color="gray", lw=0.6, ls="--")
ax.set_xscale("log")
ax.set(xlabel="impact speed (m/s)", ylabel="restitution", title="test 3: restitution against CoR (dashed)")
ax.legend(fontsize=7)


def panel(ax, runs, xlabel, title, xs=None):
    x = [r[0] for r in runs]
    for k, (label, c) in enumerate((("tangential speed", "C0"), ("spin x R", "C1"))):
        ax.plot(x, [r[3][k] for r in runs], "o", color=c, label=f"engine: {label}")
        ax.plot(x, [r[4][k] for r in runs], "-", color=c, lw=1, label=f"rigid theory: {label}")
    sl = [r[0] for r in runs if not r[2]]
    if sl:
        ax.axvspan(min(sl), max(sl), color="gray", alpha=0.15, label="contact sticks (not judged)")
    ax.set(xlabel=xlabel, ylabel="after impact (m/s)", title=title)
    ax.legend(fontsize=6)


panel(axes[0][2], [(a, None, s, m, t) for a, _, s, m, t, *_ in t4], "incidence from the normal (deg)",
      "test 4: 3.9 m/s at varying incidence")
panel(axes[1][0], t5, "tangential speed (m/s)", "test 5: v_n = 5 m/s, varying v_t")
panel(axes[1][1], t6, "spin (rad/s)", "test 6: v_n = 5 m/s, varying spin")
panel(axes[1][2], t7, "both spins w (rad/s)", "test 7: two equal spheres (sphere A)")
case.save(fig)
case.finish()
