"""The wheel of the active-box case (cases/wheel.py, paper s. 6.5.2): a soil bin of settled grains, a
grousered wheel built in code, and one drive of the wheel at a set slip over the whole bed active or
with an active box that follows the wheel.

The bin is as wide as the wheel (2 mm wider; its side walls frictionless against the grains), as a
glass-walled soil bin: the flow is plane, and no grain passes beside the wheel. Every solver is built
the same way up to Initialize() (build), so the bed settled once (settle, which writes a checkpoint)
is read back by every drive: the wheel is in the scene from the start, parked above the bed in a
fixed family, and a drive moves it into place and sets its motion after ReadCheckpoint (which
restores the settle run's family rules).

Families: 0 the bed's active grains, 1 dormant grains (fixed, no contacts among themselves, with the
wheel or with the parked wheel: docs/active-box.md), 10 the driven wheel, 11 the parked wheel
(fixed), 20 the bin's walls.
"""
import math
import time

import numpy as np

# Grains: three sizes (r = 2.25, 2.5, 2.75 mm, equally many), E = 10 MPa, nu = 0.3, CoR = 0.3,
# mu = 0.5, Crr = 0.05, 2500 kg/m^3. dt is 9 % of the mean grain's Rayleigh time (2.2e-4 s).
R_GRAIN = 0.0025
SIZES = (0.9, 1.0, 1.1)
RHO = 2500.0
MATERIAL = {"E": 1e7, "nu": 0.3, "CoR": 0.3, "mu": 0.5, "Crr": 0.05}
DT = 2e-5
G = 9.81
# The wheel: rim radius 40 mm, 40 mm wide, 12 grousers 5 mm high across its width (thin plates), a
# closed cylinder of 48 segments; 0.15 kg (a load of 1.47 N, 37 N per metre of width); driven
# forward at 0.2 m/s.
R_WHEEL, W_WHEEL, N_SEG = 0.04, 0.04, 48
N_GROUSER, H_GROUSER = 12, 0.005
M_WHEEL = 0.15
V_WHEEL = 0.2
REACH = R_WHEEL + H_GROUSER  # the wheel's outer radius (grouser tips)
F_BED, F_DORMANT, F_WHEEL, F_PARKED, F_WALL = 0, 1, 10, 11, 20
# A fixed detection schedule (CD_FREQ steps, synchronous), or the engine's adaptive one (None). The
# box's family changes are checked at contact detections, so they take effect at steps that depend
# on the schedule; the adaptive n_max follows measured costs, so with it two runs of the same box
# drive differ (a whole-bed run does not: its trajectory is independent of the schedule). The case
# fixes it on the CPU, whose runs are then reproducible bit for bit; the GPU's are not anyway.
CD_FREQ = None


def grain_mass(r):
    return RHO * 4.0 / 3.0 * math.pi * r ** 3


def grouser_period(slip):
    """Time between two grousers' passages at `slip` (s)."""
    return 2.0 * math.pi / (N_GROUSER * spin(slip))


def spin(slip):
    """The wheel's prescribed spin (rad/s): V_WHEEL = spin R_WHEEL (1 - slip), slip on the rim radius."""
    return V_WHEEL / (R_WHEEL * (1.0 - slip))


def wheel_mesh():
    """Vertices and faces of the wheel about the y axis, centred at the origin: a closed cylinder
    (tread and two caps) and N_GROUSER radial plates on the tread, each two triangles whose root edge
    is a tread edge (same vertices, so welded). Grouser k stands at angle 2 pi k / N_GROUSER from +x
    towards +z: grouser 9 points straight down in the initial pose."""
    v, f = [], []
    for side in (-0.5, 0.5):
        for i in range(N_SEG):
            a = 2 * math.pi * i / N_SEG
            v.append([R_WHEEL * math.cos(a), side * W_WHEEL, R_WHEEL * math.sin(a)])
    c0 = len(v)
    v += [[0.0, -0.5 * W_WHEEL, 0.0], [0.0, 0.5 * W_WHEEL, 0.0]]
    for i in range(N_SEG):
        j = (i + 1) % N_SEG
        f += [[i, N_SEG + i, N_SEG + j], [i, N_SEG + j, j], [c0, i, j], [c0 + 1, N_SEG + j, N_SEG + i]]
    for k in range(N_GROUSER):
        i = k * (N_SEG // N_GROUSER)
        a = 2 * math.pi * i / N_SEG
        tip = len(v)
        v += [[REACH * math.cos(a), -0.5 * W_WHEEL, REACH * math.sin(a)],
              [REACH * math.cos(a), 0.5 * W_WHEEL, REACH * math.sin(a)]]
        f += [[i, N_SEG + i, tip + 1], [i, tip + 1, tip]]
    return np.array(v, dtype=np.float64), np.array(f, dtype=np.int32)


class Bin:
    """The soil bin: x in [0, length] (the wheel drives in +x), y in [-width/2, width/2] with
    width = W_WHEEL + 2 mm, grains filled to about `depth` (then settled); the wheel's axle starts at
    x = x0 and drives `travel` metres."""

    def __init__(self, length, depth, x0, travel):
        self.length, self.depth, self.x0, self.travel = length, depth, x0, travel
        self.width = W_WHEEL + 0.002
        self.top = depth + 2 * REACH + 0.05  # the domain's height; the parked wheel sits at its top

    def grains(self):
        """Initial grain centres and size indices: a hexagonal close packing of spacing 2.02 times the
        largest radius (no two grains touch), each site given one of the three sizes at random."""
        import deme
        rmax = SIZES[-1] * R_GRAIN
        half = [self.length / 2 - rmax - 1e-4, self.width / 2 - rmax - 1e-4, self.depth / 2]
        pts = np.asarray(deme.HCPSampler(2.02 * rmax).SampleBox([self.length / 2, 0.0, self.depth / 2 + rmax], half))
        return pts, np.random.default_rng(7).integers(0, len(SIZES), len(pts))

    def radii(self):
        return np.array(SIZES)[self.grains()[1]] * R_GRAIN


def build(deme, b):
    """A solver with the bin, its grains and the parked wheel, initialised: (sim, bed batch, wheel).
    The same in every process, as a checkpoint's reader must be."""
    sim = deme.DEMSolver()
    sim.SetVerbosity("WARNING")
    mat = sim.LoadMaterial(MATERIAL)
    glass = sim.LoadMaterial(MATERIAL)  # the side walls: frictionless against the grains
    sim.SetMaterialPropertyPair("mu", mat, glass, 0.0)
    sim.SetMaterialPropertyPair("Crr", mat, glass, 0.0)
    sim.InstructBoxDomainDimension((0.0, b.length), (-b.width / 2, b.width / 2), (0.0, b.top))
    for p, n, m in (([0, 0, 0], [0, 0, 1], mat), ([0, 0, 0], [1, 0, 0], mat), ([b.length, 0, 0], [-1, 0, 0], mat),
                    ([0, -b.width / 2, 0], [0, 1, 0], glass), ([0, b.width / 2, 0], [0, -1, 0], glass)):
        sim.AddBCPlane(p, n, m).SetFamily(F_WALL)
    pts, size = b.grains()
    tmpls = [sim.LoadSphereType(grain_mass(s * R_GRAIN), s * R_GRAIN, mat) for s in SIZES]
    bed = sim.AddClumps([tmpls[i] for i in size], pts)
    bed.SetFamily(F_BED)
    v, f = wheel_mesh()
    wheel = sim.AddWavefrontMeshObject(deme.DEMMeshConnected(v, f, mat))
    wheel.SetMass(M_WHEEL)
    i_axle = 0.5 * M_WHEEL * R_WHEEL ** 2
    wheel.SetMOI([0.5 * i_axle, i_axle, 0.5 * i_axle])
    wheel.SetFamily(F_PARKED)
    wheel.SetInitPos([b.x0, 0.0, b.top - REACH - 0.005])
    sim.SetFamilyFixed(F_PARKED)
    sim.SetFamilyFixed(F_DORMANT)
    sim.DisableContactBetweenFamilies(F_PARKED, F_BED)
    sim.DisableContactBetweenFamilies(F_PARKED, F_DORMANT)
    sim.DisableContactBetweenFamilies(F_DORMANT, F_DORMANT)
    sim.DisableContactBetweenFamilies(F_WHEEL, F_DORMANT)
    sim.SetInitTimeStep(DT)
    sim.SetGravitationalAcceleration([0, 0, -G])
    sim.SetErrorOutVelocity(20.0)
    if CD_FREQ:
        sim.SetSynchronousContactDetection(True)
        sim.DisableAdaptiveUpdateFreq()
        sim.SetCDUpdateFreq(CD_FREQ)
    sim.Initialize()
    return sim, bed, wheel


def settle(deme, b, path, t_settle):
    """Settles the bed for t_settle s and writes the checkpoint to `path`. Returns a dict: grains,
    the bed's kinetic energy over (grains x weight x radius) at the end, the surface height under
    the wheel's path (surface), and the wall time."""
    t0 = time.time()
    sim, bed, _ = build(deme, b)
    sim.DoDynamics(t_settle)
    tr = sim.Track(bed)
    n = tr.GetNumOwners()
    ke = sim.CreateInspector("clump_kinetic_energy").GetValue() / (n * grain_mass(R_GRAIN) * G * R_GRAIN)
    pos = tr.Positions()
    sim.WriteCheckpoint(path)
    return {"grains": n, "ke": ke, "surface": surface(b, pos, b.radii()), "wall": time.time() - t0,
            "positions": pos}


def surface(b, pos, radii):
    """The bed's surface height under the wheel's path: the mean, over 1 cm x 1 cm cells of the strip
    |y| < W_WHEEL / 2 from x0 - REACH to x0 + travel + REACH, of the highest grain top in each cell."""
    tops = []
    for x in np.arange(b.x0 - REACH, b.x0 + b.travel + REACH - 1e-9, 0.01):
        for y in np.arange(-W_WHEEL / 2, W_WHEEL / 2 - 1e-9, 0.01):
            m = (pos[:, 0] >= x) & (pos[:, 0] < x + 0.01) & (pos[:, 1] >= y) & (pos[:, 1] < y + 0.01)
            if np.any(m):
                tops.append(float(np.max(pos[m, 2] + radii[m])))
    return float(np.mean(tops))


def drive(deme, b, path, z_surface, slip, t_run, sample_steps, box=None, snapshots=0, nudge=0.0):
    """Reads the settled bed from `path` and drives the wheel for t_run s at `slip`: forward speed
    V_WHEEL and spin (slip) prescribed, vertical motion free under its weight; it starts at rest
    vertically with its lowest grouser's tip at z_surface. box: None for the whole bed active, else
    (back, front, hysteresis): grains whose centre is less than `back` behind and `front` ahead of
    the axle are active, those more than back + hysteresis behind or front + hysteresis ahead fall
    dormant where they are (checked at every contact detection). nudge: lifts the grain farthest
    ahead by that much at the start (the scatter control). Samples every sample_steps steps the
    contact force on the wheel (x, z) and its height; every 25 samples, with a box, the active grains
    and the gap between the wheel's reach and the nearest dormant grain. With snapshots > 0, also
    that many bed position snapshots. Returns a dict of arrays and the stepping's wall time."""
    sim, bed, wheel = build(deme, b)
    sim.ReadCheckpoint(path)
    t_start = sim.GetSimTime()
    bed_tr, wtr = sim.Track(bed), sim.Track(wheel)
    z0 = z_surface + REACH
    wtr.SetPos([b.x0, 0.0, z0])
    sim.SetFamilyPrescribedLinVel(F_WHEEL, repr(V_WHEEL), "0", "none")
    sim.SetFamilyPrescribedAngVel(F_WHEEL, "0", repr(spin(slip)), "0")
    wtr.SetFamily(F_WHEEL)
    pos = bed_tr.Positions()
    radii = b.radii()
    if nudge:
        i = int(np.argmax(pos[:, 0]))
        bed_tr.SetPos([float(pos[i, 0]), float(pos[i, 1]), float(pos[i, 2]) + nudge], i)
    if box is not None:
        back, front, hyst = box
        xw = f"({b.x0!r} + {V_WHEEL!r} * (t - {t_start!r}))"  # the axle's x: its speed is prescribed
        inside = (pos[:, 0] - b.x0 > -back) & (pos[:, 0] - b.x0 < front)
        bed_tr.SetFamilies(np.where(inside, F_BED, F_DORMANT).astype(np.uint32))
        sim.ChangeFamilyWhen(F_DORMANT, F_BED, f"X - {xw} > {-back!r} && X - {xw} < {front!r}")
        sim.ChangeFamilyWhen(F_BED, F_DORMANT, f"X - {xw} < {-(back + hyst)!r} || X - {xw} > {front + hyst!r}")
    n = int(round(t_run / (sample_steps * DT)))
    out = {"t": np.zeros(n), "fx": np.zeros(n), "fz": np.zeros(n), "z": np.zeros(n), "z0": z0,
           "active": [], "gap": []}
    snap_every = max(1, n // snapshots) if snapshots else 0
    snaps = [(0.0, pos.copy())] if snapshots else []
    ever_active = np.zeros(len(pos), dtype=bool)
    t0 = time.time()
    for k in range(n):
        sim.DoDynamics(sample_steps * DT)
        out["t"][k] = sim.GetSimTime() - t_start
        f = wtr.ContactForce()
        out["fx"][k], out["fz"][k] = f[0], f[2]
        w = wtr.Pos()
        out["z"][k] = w[2]
        if box is not None and (k % 25 == 0 or k == n - 1):
            fam = bed_tr.GetFamilies()
            p = bed_tr.Positions()
            active = fam == F_BED
            ever_active |= active
            d = np.hypot(p[~active, 0] - w[0], p[~active, 2] - w[2]) - radii[~active] - REACH
            out["active"].append((out["t"][k], int(np.count_nonzero(active))))
            out["gap"].append(float(d.min()) if len(d) else math.inf)
        if snap_every and (k + 1) % snap_every == 0:
            snaps.append((out["t"][k], bed_tr.Positions().copy()))
    out["wall"] = time.time() - t0
    out["snaps"] = snaps
    out["ever_active"] = ever_active
    out["x_end"] = float(wtr.Pos()[0])
    return out


def outside_motion(b, snaps, back, front):
    """From the whole-bed run's snapshots: each grain's summed displacement over the intervals at
    whose start its centre lay outside the box [axle - back, axle + front], i.e. how far the grains
    that the box holds dormant moved in the whole-bed run (m, one value per grain)."""
    moved = np.zeros(len(snaps[0][1]))
    for (t_a, p_a), (_, p_b) in zip(snaps[:-1], snaps[1:]):
        rel = p_a[:, 0] - (b.x0 + V_WHEEL * t_a)
        moved += np.where((rel < -back) | (rel > front), np.linalg.norm(p_b - p_a, axis=1), 0.0)
    return moved


def window_means(run, slip, t_from):
    """Means of the drawbar pull (contact force along +x, N) and sinkage (m) over the largest whole
    number of grouser periods between t_from and the run's end, and their standard errors from the
    spread of the per-period means. Returns (dp, dp_se, sinkage, sinkage_se, periods, window start)."""
    t = run["t"]
    dt = t[1] - t[0]
    m = int(round(grouser_period(slip) / dt))
    k = int((t[-1] - t_from) / (m * dt) + 1e-9)
    i0 = len(t) - k * m
    sink = run["z0"] - run["z"]
    per_dp = [run["fx"][i0 + j * m:i0 + (j + 1) * m].mean() for j in range(k)]
    per_s = [sink[i0 + j * m:i0 + (j + 1) * m].mean() for j in range(k)]
    se = (lambda v: float(np.std(v, ddof=1) / math.sqrt(len(v))) if len(v) > 1 else math.nan)
    return float(np.mean(per_dp)), se(per_dp), float(np.mean(per_s)), se(per_s), k, float(t[i0] - dt)
