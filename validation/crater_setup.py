"""The ball impact of the paper's s. 6.1 (Uehara et al. 2003; Ambroso et al. 2005), for the crater case:
a bed of grains poured into a box and settled once, then each ball dropped on that same settled bed
(restored from a checkpoint before every drop) and its penetration depth measured once it is at rest.

Grains: diameters 0.25 to 0.35 cm in 11 sizes evenly spread, each size equally likely, rho = 2.5 g/cm^3,
mu = 0.3 (paper s. 6.1); E = 10 MPa, nu = 0.3, CoR = 0.5, Crr = 0 (our choice: the paper gives no
more). The balls: D = 2.54 cm, of the grains' material. Walls (the box's, `top_open`) too. Step: 10 %
of the smallest grain's Rayleigh time (1.08e-5 s). SI units inside; the law is written in cm.
"""
import math

import numpy as np

from settling import step_until_still

G = 9.81
RHO_GRAIN = 2500.0
MU = 0.3
E, NU, COR = 1e7, 0.3, 0.5
RADII = np.linspace(0.00125, 0.00175, 11)  # diameters 0.25-0.35 cm
BALL_D = 0.0254
LATTICE = 0.0036  # the poured cloud's lattice: just over the largest diameter
# Families: grains 0; the balls waiting out of play 1 (fixed, touching nothing); the ball in play 2.
PARKED, FREE = 1, 2
# The synchronous detection's adaptive n_max grows to its cap (200) while the bed is still and does
# not come down when the ball is released: its margin, sized by the ball's 2 m/s for every grain,
# then keeps ~99 % false pairs and the step runs ~15 times slower. Capped here (any cap gives the same
# trajectory, docs/physics.md; this one is only about speed).
MAX_UPDATE_FREQ = 30


def sphere_mass(r, rho):
    return rho * 4.0 / 3.0 * math.pi * r ** 3


class Bed:
    """A box of half-width `half` (m) poured to about `depth` (m), with one parked ball per density;
    `grain_scale` multiplies every grain's diameter (and the poured lattice and the surface's cells)."""

    def __init__(self, deme, half, depth, ball_densities, seed=1, grain_scale=1.0):
        self.half, self.depth, self.scale = half, depth, grain_scale
        radii, lattice = RADII * grain_scale, LATTICE * grain_scale
        sim = self.sim = deme.DEMSolver()
        sim.SetVerbosity("WARNING")
        mat = sim.LoadMaterial({"E": E, "nu": NU, "CoR": COR, "mu": MU, "Crr": 0.0})
        # The cloud fills about 0.31 of its volume (a cubic lattice of 3.6 mm): a little under twice
        # the settled bed's height.
        top = 2.0 * depth + 0.06 + 2 * BALL_D
        sim.InstructBoxDomainDimension((-half, half), (-half, half), (0.0, top))
        sim.InstructBoxDomainBoundingBC("top_open", mat)
        types = [sim.LoadSphereType(sphere_mass(r, RHO_GRAIN), float(r), mat) for r in radii]
        # The cloud: lattice points moved by up to 0.1 mm, each grain of a random size, falling at 0.5 m/s.
        rng = np.random.default_rng(seed)
        n = int(0.59 * (2 * half) ** 2 * depth / float(np.mean(4.0 / 3.0 * math.pi * radii ** 3)))
        xs = np.arange(-half + 0.5 * lattice + 2e-4, half - 0.5 * lattice - 2e-4, lattice)
        zs = 0.5 * lattice + 2e-4 + lattice * np.arange(math.ceil(n / len(xs) ** 2))
        Z, X, Y = np.meshgrid(zs, xs, xs, indexing="ij")
        pts = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)[:n]
        pts += rng.uniform(-1e-4, 1e-4, pts.shape)
        kind = rng.integers(0, len(radii), len(pts))
        self.r = radii[kind]
        self.grains = sim.AddClumps([types[k] for k in kind], pts)
        self.grains.SetVel(np.tile([0.0, 0.0, -0.5], (len(pts), 1)))
        # The balls wait in a row near the domain's top, fixed and touching nothing.
        rb = 0.5 * BALL_D
        ball_types = [sim.LoadSphereType(sphere_mass(rb, rho), rb, mat) for rho in ball_densities]
        self.balls = sim.AddClumps(ball_types, [[-half + (1.2 + 2.2 * i) * rb, 0.0, top - 1.2 * rb]
                                                for i in range(len(ball_types))])
        self.balls.SetFamily(PARKED)
        sim.SetFamilyFixed(PARKED)
        for f in (0, PARKED, FREE):
            sim.DisableContactBetweenFamilies(PARKED, f)
        self.dt = 0.1 * deme.RayleighTime(float(radii[0]), RHO_GRAIN, E, NU)
        sim.SetInitTimeStep(self.dt)
        sim.SetGravitationalAcceleration([0.0, 0.0, -G])
        sim.SetErrorOutVelocity(20.0)
        sim.SetCDMaxUpdateFreq(MAX_UPDATE_FREQ)
        sim.Initialize()
        self.grain_tr = sim.Track(self.grains)
        self.ball_tr = sim.Track(self.balls)
        self.n = len(pts)

    def settle(self, t_min=0.15, t_max=1.5, v_mean=5e-4, v_max=0.05, frame=0.02):
        """Pours the cloud and lets it settle, until the grains' mean speed is below v_mean and the
        fastest one's (a rattler on the surface) below v_max (m/s); returns the time it took and the
        fastest grain's speed then."""
        t, _, fastest = step_until_still(self.sim, self.grain_tr, t_min, t_max, v_mean, v_max, frame)
        return t, fastest

    def measure(self):
        """The settled bed: its surface level about the drop point (surface_level), its bulk density
        inside (the grains whose centres lie 1 cm or more from the walls, the floor and the surface,
        over the volume of that block) and over the whole bed (all grains over the box up to the
        surface level), in kg/m^3."""
        p = self.grain_tr.Positions()
        self.surface = surface_level(p, self.r, 2.0 * BALL_D, 0.006 * self.scale)
        z, w, lo, hi = p[:, 2], self.half - 0.01, 0.01, self.surface - 0.01
        inside = (z > lo) & (z < hi) & (np.abs(p[:, 0]) < w) & (np.abs(p[:, 1]) < w)
        vol = 4.0 / 3.0 * math.pi * self.r ** 3
        self.rho_inside = RHO_GRAIN * float(vol[inside].sum()) / ((2 * w) ** 2 * (hi - lo))
        self.rho_whole = RHO_GRAIN * float(vol.sum()) / ((2 * self.half) ** 2 * self.surface)
        return self.surface, self.rho_inside

    def drop(self, k, h, t_max=0.6, frame=0.005, v_rest=0.005):
        """Drops ball k on the axis from h (m, its bottom above the surface level) onto the bed as it is
        now. Returns its penetration depth (m) below the surface level once at rest (slower than
        v_rest for four frames in a row), its path (times, depths) and whether it came to rest."""
        sim, tr, rb = self.sim, self.ball_tr, 0.5 * BALL_D
        p = self.grain_tr.Positions()
        # Released 1 mm above the highest grain under it, with the speed of a fall from h.
        under = np.hypot(p[:, 0], p[:, 1]) < rb + 0.002
        gap = float(np.max(p[under, 2] + self.r[under])) + 0.001 - self.surface
        tr.SetPos([0.0, 0.0, self.surface + gap + rb], k)
        tr.SetVel([0.0, 0.0, -math.sqrt(2.0 * G * (h - gap))], k)
        tr.SetAngVel([0.0, 0.0, 0.0], k)
        tr.SetFamily(FREE, k)
        t0 = sim.GetSimTime()
        path_t, path_d, still = [0.0], [-gap], 0
        while sim.GetSimTime() - t0 < t_max and still < 4:
            sim.DoDynamics(frame)
            path_t.append(sim.GetSimTime() - t0)
            path_d.append(self.surface - (float(tr.Pos(k)[2]) - rb))
            still = still + 1 if path_d[-1] > 0 and float(np.linalg.norm(tr.Vel(k))) < v_rest else 0
        return path_d[-1], np.array(path_t), np.array(path_d), still >= 4


def surface_level(p, r, radius, cell=0.006):
    """The surface's height about the axis: on a square grid of cells about two grain diameters wide,
    the top of each cell's highest grain, averaged over the cells whose centres lie within `radius`
    (where a ruler laid on the surface would rest)."""
    ix = np.floor(p[:, 0] / cell).astype(int)
    iy = np.floor(p[:, 1] / cell).astype(int)
    tops = {}
    for i, j, z in zip(ix, iy, p[:, 2] + r):
        tops[(i, j)] = max(z, tops.get((i, j), -1.0))
    near = [z for (i, j), z in tops.items() if math.hypot((i + 0.5) * cell, (j + 0.5) * cell) < radius]
    return float(np.mean(near))


def law_abscissa(rho_b, rho_g, h, d):
    """(1/mu) (rho_b/rho_g)^(1/2) D^(2/3) H^(1/3) with H = h + d, lengths in m (the paper's Eq. for d
    is d = C times this)."""
    return (1.0 / MU) * math.sqrt(rho_b / rho_g) * BALL_D ** (2.0 / 3.0) * (h + d) ** (1.0 / 3.0)


def fit_constant(x, d):
    """Least squares of d = C x (the law has no intercept); returns C and R^2 (about the mean of d)."""
    x, d = np.asarray(x, float), np.asarray(d, float)
    c = float(np.dot(x, d) / np.dot(x, x))
    return c, 1.0 - float(np.sum((d - c * x) ** 2) / np.sum((d - d.mean()) ** 2))
