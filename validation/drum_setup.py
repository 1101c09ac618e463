"""The rotating drum of the paper's s. 6.2.1, shared by validation/cases/drum.py: many drums in one
simulation (one per (mu, Crr) point), their free-surface angle, and the same drums in LIGGGHTS 3.8
(drum_liggghts.in).

Contact model: Hertz-Mindlin as the engine's default, with a rolling resistance that opposes the
grains' relative spin (validation/rolling_model.py, LIGGGHTS's `cdt`) rather than the default's
(paper s. 3.1), which between grains is no rolling resistance (that file says why);
DrumSet(rolling="paper") takes the default model.

Geometry: a drum of inner diameter D = 0.19 m and depth W (the paper's 0.20 m, or thinner: a
parameter) turning about its axis (y, horizontal; gravity along -z) at 3.6 rpm, the positive sense
about +y, so that the bed rises on the -x side. Its mantle (an analytical cylinder) and its two end
walls (planes) turn with it. Walls as in the paper's own drum demos: E = 10 GPa, nu = 0.3,
grain-wall CoR 0.5 and mu 0.30 whatever the grains' mu; grain-wall Crr 0 (WALL_PAIR, below).
The drums of one simulation stand apart in the x-z plane; each drum's grains have a family of their
own, whose contacts with every other drum are disabled (the analytical walls are infinite).

Grains (the paper's particle table): PS, spheres of r = 3 mm, rho = 1592 kg/m^3; PC, "cylinders" of
5 spheres of r = 2 mm with centres 1 mm apart on the axis (8 mm long), with a solid cylinder's mass
and inertia (r = 2 mm, L = 8 mm, 1128 kg/m^3: 1.134e-4 kg), as the paper's demo gives them. Both:
E = 10 MPa, nu = 0.35, CoR = 0.85. Number: the paper's count per unit depth (13,024 PS and 19,036 PC
in 0.20 m), which it calls half filled.

Free surface: in the drum's cross-section (x, z relative to its axis; all grains, whatever their y),
bins two volume-equivalent diameters d wide over the middle of the drum (|x| <= R/2); in each bin the
surface height is the mean centre height of its top k grains, k = half a monolayer of the bin (bin
width x W / d^2 / 2, at least 2); a straight line is fitted through the bins' heights by least
squares, and the angle is atan(-slope) (positive when the bed rises on the side the mantle carries
up).
"""
import math
import os
import shutil
import subprocess

import numpy as np

import rolling_model

D_DRUM = 0.19
R_DRUM = D_DRUM / 2
RPM = 3.6
OMEGA = RPM * 2 * math.pi / 60  # rad/s about +y
G = 9.81
E, NU, COR = 1e7, 0.35, 0.85
# The walls, as in the paper's own drum demos (projectchrono/DEM-Engine, src/demo/
# DEMdemo_Granular_PlasticSphereDrum.cpp and ..._PlasticCylinderDrum.cpp, 2023): E = 10 GPa, nu = 0.3,
# and for every grain-wall pair CoR = 0.5 and mu = 0.30, whatever the grains' own mu. The demos' wall
# Crr of 0.05 is left at 0: against a turning wall the rolling model (rolling_model.py) takes the
# wall's spin into the relative spin, LIGGGHTS's takes the grain's alone, so with a wall Crr the two
# codes would not run the same model.
WALL_E, WALL_NU = 1e10, 0.3
WALL_PAIR = {"CoR": 0.5, "mu": 0.30, "Crr": 0.0}
HERE = os.path.dirname(os.path.abspath(__file__))


class Grain:
    """One of the paper's grain kinds: component spheres (in the clump frame, axis x), mass and MOI
    (a sphere's; for the cylinders a solid cylinder's, r and length L, as the paper's demo does),
    count per metre of depth."""

    def __init__(self, name, radius, rho, spheres, per_metre):
        self.name, self.radius, self.rho, self.per_metre = name, radius, rho, per_metre
        self.spheres = np.array(spheres, float)  # (k, 3) centres in the clump frame
        self.length = float(np.ptp(self.spheres[:, 0]) + 2 * radius)  # along the clump's axis (x)
        if len(self.spheres) == 1:
            self.volume = 4 / 3 * math.pi * radius ** 3
            self.mass = rho * self.volume
            self.moi = [0.4 * self.mass * radius ** 2] * 3
        else:
            self.volume = math.pi * radius ** 2 * self.length
            self.mass = rho * self.volume
            i_axis = 0.5 * self.mass * radius ** 2
            i_cross = i_axis / 2 + self.mass * self.length ** 2 / 12
            self.moi = [i_axis, i_cross, i_cross]
        # volume-equivalent diameter of the grain's shape (the spheres' union for the clumps)
        shape_volume = self.volume if len(self.spheres) == 1 else union_volume(self.spheres, radius)
        self.d_eq = (6 * shape_volume / math.pi) ** (1 / 3)

    def count(self, depth):
        return int(round(self.per_metre * depth))


def union_volume(centres, r, h=5e-5):
    """Volume of a union of equal spheres, on a grid of spacing h."""
    lo = centres.min(axis=0) - r
    hi = centres.max(axis=0) + r
    axes = [np.arange(lo[i] + h / 2, hi[i], h) for i in range(3)]
    X, Y, Z = np.meshgrid(*axes, indexing="ij")
    inside = np.zeros(X.shape, bool)
    for c in centres:
        inside |= (X - c[0]) ** 2 + (Y - c[1]) ** 2 + (Z - c[2]) ** 2 <= r * r
    return float(inside.sum() * h ** 3)


PS = Grain("PS", 0.003, 1592.0, [[0, 0, 0]], 13024 / 0.20)
PC = Grain("PC", 0.002, 1128.0, [[-0.002, 0, 0], [-0.001, 0, 0], [0, 0, 0], [0.001, 0, 0], [0.002, 0, 0]],
           19036 / 0.20)
GRAINS = {"PS": PS, "PC": PC}


# ---------------------------------------------------------------------------------------------
# The initial packing of one drum (drum frame: axis along y through the origin)

def loose_packing(grain, depth, seed=1, tilt=0.0):
    """Positions (n, 3) and orientations (n, 4; x, y, z, w) of the grains of one drum, on a loose
    lattice filling the drum from its bottom (the lowest n sites): spheres on a cubic lattice of
    2.2 r, each moved by up to 0.1 r in every direction; cylinders in 2 x 2 bundles of four parallel
    clumps filling cubes of side L + 0.4 mm, each cube's axis x, y or z at random, each clump moved
    by up to 0.08 mm. They settle into a bed under gravity before the drum turns. The sites kept are
    the lowest along the normal of a surface tilted by `tilt` degrees (rising on the -x side, as
    the turning drum lifts it), so that less turning brings the bed to its angle."""
    nrm = np.array([math.sin(math.radians(tilt)), 0.0, math.cos(math.radians(tilt))])
    rng = np.random.default_rng(seed)
    n = grain.count(depth)
    r = grain.radius
    margin = 0.3e-3
    if len(grain.spheres) == 1:
        # a face-centred cubic lattice of nearest distance 2.2 r, each grain moved by up to 0.1 r in
        # every direction (without a y jitter the layers of a thin drum would stay apart)
        jit = 0.1 * r
        a = 2.2 * r * math.sqrt(2)
        lim = depth / 2 - r - jit - margin
        cells = np.arange(-int(R_DRUM / a) - 1, int(R_DRUM / a) + 2)
        basis = np.array([[0, 0, 0], [0, 0.5, 0.5], [0.5, 0, 0.5], [0.5, 0.5, 0]]) * a
        cy = np.arange(-int(depth / a) - 1, int(depth / a) + 2)
        grid = np.array([[i, j, k] for i in cells for j in cy for k in cells], float) * a
        pts = (grid[:, None, :] + basis[None, :, :]).reshape(-1, 3)
        pts += rng.uniform(-jit, jit, pts.shape)
        ok = (np.hypot(pts[:, 0], pts[:, 2]) < R_DRUM - r - jit - margin) & (np.abs(pts[:, 1]) <= lim)
        pts = pts[ok]
        pts = pts[np.argsort(pts @ nrm, kind="stable")]
        if len(pts) < n:
            raise ValueError(f"the lattice holds {len(pts)} of {n} grains")
        return pts[:n], np.tile([0.0, 0.0, 0.0, 1.0], (n, 1))
    # Cylinders: cubes of side c = L + gap hold 4 parallel clumps (2 x 2, centres +-c/4 across the
    # axis); the cube's axis is x, y or z at random.
    L = grain.length
    c = max(L, 4 * r) + 0.4e-3
    half = c / 2
    ny = int((depth - 2 * margin) // c)
    ys = (np.arange(ny) - (ny - 1) / 2) * c
    xs = np.arange(-R_DRUM, R_DRUM + c, c)
    zs = np.arange(-R_DRUM + half + margin, R_DRUM, c)
    cubes = np.array([[x, y, z] for z in zs for x in xs for y in ys])
    corner = half * math.sqrt(2)  # the cube's corner distance in the x-z plane
    cubes = cubes[np.hypot(cubes[:, 0], cubes[:, 2]) < R_DRUM - corner - margin]
    cubes = cubes[np.argsort(cubes @ nrm, kind="stable")]
    q_axis = {0: [0.0, 0.0, 0.0, 1.0],  # clump x along global x
              1: [0.0, 0.0, math.sin(math.pi / 4), math.cos(math.pi / 4)],  # x -> y (90 deg about z)
              2: [0.0, -math.sin(math.pi / 4), 0.0, math.cos(math.pi / 4)]}  # x -> z (-90 deg about y)
    pts, qs = [], []
    for cube in cubes:
        a = int(rng.integers(3))
        across = [i for i in range(3) if i != a]
        for u in (-c / 4, c / 4):
            for v in (-c / 4, c / 4):
                p = cube.copy()
                p[across[0]] += u
                p[across[1]] += v
                pts.append(p)
                qs.append(q_axis[a])
    pts, qs = np.array(pts), np.array(qs)
    pts += rng.uniform(-0.08e-3, 0.08e-3, pts.shape)  # within the 0.2 mm gaps of a bundle
    if len(pts) < n:
        raise ValueError(f"the lattice holds {len(pts)} of {n} clumps")
    return pts[:n], qs[:n]


# ---------------------------------------------------------------------------------------------
# The engine: one simulation holding a drum per (mu, Crr) point

def drum_centres(count, spacing=None):
    """Drum centres on a grid in the x-z plane (rows of up to 8 drums)."""
    spacing = spacing or D_DRUM + 0.03
    cols = min(count, 8)
    return np.array([[(k % cols) * spacing, 0.0, (k // cols) * spacing] for k in range(count)])


class DrumSet:
    """Drums of one grain kind and depth, one per (mu, Crr) point, settled, then turned."""

    def __init__(self, deme, grain, depth, points, settle=0.3, dt=2e-5, young=E, tilt=30.0, seed=1,
                 max_cd_interval=20, verbose="WARNING", rolling="relative", seeds=None):
        # rolling: "relative", the rolling resistance of rolling_model.py (a couple against the
        # relative spin, as LIGGGHTS's cdt); "paper", the default model's (paper s. 3.1).
        # seeds: one per drum (its packing's jitter), where drums of one point are replicas; by
        # default every drum starts from the packing of `seed`.
        self.grain, self.depth, self.points = grain, depth, list(points)
        seeds = list(seeds) if seeds is not None else [seed] * len(self.points)
        if len(seeds) != len(self.points):
            raise ValueError(f"{len(seeds)} seeds for {len(self.points)} drums")
        self.dt = dt
        self.settle = settle
        n_d = len(self.points)
        if n_d > 120:
            raise ValueError("at most 120 drums per simulation (a family each for grains and drum)")
        self.centres = drum_centres(n_d)
        packings = {k: loose_packing(grain, depth, k, tilt) for k in sorted(set(seeds))}
        self.n = len(packings[seeds[0]][0])
        sim = deme.DEMSolver()
        sim.SetVerbosity(verbose)
        lo = self.centres.min(axis=0) - R_DRUM - 0.01
        hi = self.centres.max(axis=0) + R_DRUM + 0.01
        sim.InstructBoxDomainDimension((lo[0], hi[0]), (-depth / 2 - 0.01, depth / 2 + 0.01), (lo[2], hi[2]))
        self.batches = []
        # rotation starts once the grains have settled
        spin = f"{OMEGA!r} * fmin(1.0, floor(t / {settle!r}))"
        wall = sim.LoadMaterial({"E": WALL_E, "nu": WALL_NU, "CoR": WALL_PAIR["CoR"], "mu": WALL_PAIR["mu"],
                                 "Crr": WALL_PAIR["Crr"]})
        for k, (mu, crr) in enumerate(self.points):
            mat = sim.LoadMaterial({"E": young, "nu": NU, "CoR": COR, "mu": mu, "Crr": crr})
            for prop, v in WALL_PAIR.items():
                sim.SetMaterialPropertyPair(prop, mat, wall, v)
            drum = sim.AddExternalObject()
            drum.AddCylinder([0, 0, 0], [0, 1, 0], R_DRUM, wall, 0)
            drum.AddPlane([0, -depth / 2, 0], [0, 1, 0], wall)
            drum.AddPlane([0, depth / 2, 0], [0, -1, 0], wall)
            drum.SetInitPos(self.centres[k].tolist())
            drum.SetFamily(128 + k)
            sim.SetFamilyPrescribedLinVel(128 + k, "0", "0", "0")
            sim.SetFamilyPrescribedAngVel(128 + k, "0", spin, "0")
            if len(grain.spheres) == 1:
                tmpl = sim.LoadSphereType(grain.mass, grain.radius, mat)
            else:
                tmpl = sim.LoadClumpType(grain.mass, grain.moi, [grain.radius] * len(grain.spheres),
                                         grain.spheres.tolist(), mat)
            pos0, q0 = packings[seeds[k]]
            b = sim.AddClumps(tmpl, pos0 + self.centres[k])
            b.SetOriQ(q0)
            b.SetFamily(k)
            self.batches.append(b)
        for k in range(n_d):
            for j in range(n_d):
                if j != k:
                    sim.DisableContactBetweenFamilies(k, 128 + j)
        sim.SetInitTimeStep(self.dt)
        sim.SetGravitationalAcceleration([0, 0, -G])
        sim.SetErrorOutVelocity(5.0)
        # n_max capped: left to adapt, it grows to 200 while the lattice collapses (grains at up to
        # 0.8 m/s: with dt = 1e-4 s a 16 mm margin, 98 % of the contact set apart, steps ten times
        # slower on the CPU); 20 suits the CPU, the GPU's cheaper detection a longer interval
        sim.SetCDMaxUpdateFreq(max_cd_interval)
        if rolling == "relative":
            # DRUM_APART_PAIRS=called: the model called for apart pairs too (a comparison of speed)
            rolling_model.use(sim, called_for_apart_pairs=os.environ.get("DRUM_APART_PAIRS") == "called")
        elif rolling != "paper":
            raise ValueError(f"rolling must be 'relative' or 'paper', not {rolling!r}")
        sim.Initialize()
        self.sim = sim
        self.trackers = [sim.Track(b) for b in self.batches]

    def positions(self, k):
        """Grain centres of drum k in its own frame (axis through the origin)."""
        return np.asarray(self.trackers[k].Positions(), float) - self.centres[k]

    def run(self, t_steady, t_measure, samples=30, on_settled=None):
        """Settles, turns for t_steady, then measures every drum's angle `samples` times, evenly
        over t_measure (the first sample t_measure / samples after the steady phase); returns the
        angles (n_drums, samples). on_settled(states) gets the settled packings before the drums
        turn: per drum, (positions in the drum frame, velocities, angular velocities)."""
        sim = self.sim
        sim.DoDynamics(self.settle)
        if on_settled:
            on_settled([(self.positions(k), np.asarray(self.trackers[k].Velocities(), float),
                         np.asarray(self.trackers[k].AngularVelocities(), float)) for k in range(len(self.points))])
        sim.DoDynamics(t_steady)
        angles = np.zeros((len(self.points), samples))
        frame = t_measure / samples
        for s in range(samples):
            sim.DoDynamics(frame)
            for k in range(len(self.points)):
                angles[k, s] = surface_angle(self.positions(k), self.grain, self.depth)
        return angles


# ---------------------------------------------------------------------------------------------
# The measurement

def surface_profile(pos, grain, depth, span=0.5):
    """(bin centres x, surface heights z) across the middle of the drum (|x| <= span R): bins two
    volume-equivalent diameters d wide; in each, the mean height of its top k grains, k = half a
    monolayer (0.5 x bin width x depth / d^2, at least 2)."""
    width = 2 * grain.d_eq
    nb = max(2, int(2 * span * R_DRUM // width))
    edges = np.linspace(-nb * width / 2, nb * width / 2, nb + 1)
    k = max(2, int(round(0.5 * width * depth / grain.d_eq ** 2)))
    xs, zs = [], []
    for i in range(nb):
        sel = pos[(pos[:, 0] >= edges[i]) & (pos[:, 0] < edges[i + 1]), 2]
        if len(sel) < k:
            continue
        top = np.sort(sel)[-k:]
        xs.append(0.5 * (edges[i] + edges[i + 1]))
        zs.append(top.mean())
    return np.array(xs), np.array(zs)


def surface_angle(pos, grain, depth):
    x, z = surface_profile(pos, grain, depth)
    if len(x) < 3:
        return float("nan")
    slope = np.polyfit(x, z, 1)[0]
    return math.degrees(math.atan(-slope))


def centroid_angle(pos):
    """The bed's tilt from its centre of mass: for a flat surface the centroid of the circular
    segment lies on the normal to the surface through the axis."""
    cx, cz = pos[:, 0].mean(), pos[:, 2].mean()
    return math.degrees(math.atan2(-cx, -cz))


# ---------------------------------------------------------------------------------------------
# LIGGGHTS 3.8: the same drums (spheres only), from the engine's settled packing

def drum_stl(path, centre, depth, segments=96):
    """One drum's walls as triangles: the mantle, a prism of `segments` flats that lie at R_DRUM
    from the axis (vertices at R_DRUM / cos(pi / segments)), cut into rows about as long as the flats
    are wide, and both end walls (a fan at the centre and two rings: few triangles, since LIGGGHTS
    moves every node of a turning mesh each step)."""
    a = math.pi / segments
    rv = R_DRUM / math.cos(a)
    ang = 2 * math.pi * np.arange(segments) / segments
    ny = max(1, int(round(depth / (2 * rv * math.sin(a)))))
    ys = np.linspace(-depth / 2, depth / 2, ny + 1)
    cx, cz = centre[0], centre[2]
    tris = []

    def p(r, th, y):
        return (cx + r * math.cos(th), y, cz + r * math.sin(th))

    for i in range(segments):
        t0, t1 = ang[i], ang[(i + 1) % segments]
        for j in range(ny):
            y0, y1 = ys[j], ys[j + 1]
            tris.append((p(rv, t0, y0), p(rv, t1, y0), p(rv, t1, y1)))
            tris.append((p(rv, t0, y0), p(rv, t1, y1), p(rv, t0, y1)))
    # end walls: rings of about the mantle's segment width, the innermost a fan
    nr = 3
    radii = np.linspace(0, rv, nr + 1)
    for y in (-depth / 2, depth / 2):
        for i in range(segments):
            t0, t1 = ang[i], ang[(i + 1) % segments]
            tris.append(((cx, y, cz), p(radii[1], t0, y), p(radii[1], t1, y)))
            for j in range(1, nr):
                r0, r1 = radii[j], radii[j + 1]
                tris.append((p(r0, t0, y), p(r1, t0, y), p(r1, t1, y)))
                tris.append((p(r0, t0, y), p(r1, t1, y), p(r0, t1, y)))
    with open(path, "w") as out:
        out.write("solid drum\n")
        for tri in tris:
            v = np.array(tri)
            nrm = np.cross(v[1] - v[0], v[2] - v[0])
            nrm /= np.linalg.norm(nrm)
            out.write(f"facet normal {nrm[0]:.6g} {nrm[1]:.6g} {nrm[2]:.6g}\nouter loop\n")
            for x in v:
                out.write(f"vertex {x[0]:.9g} {x[1]:.9g} {x[2]:.9g}\n")
            out.write("endloop\nendfacet\n")
        out.write("endsolid drum\n")
    return len(tris)


def write_peer_files(folder, grain, depth, points, states, young=E):
    """The LIGGGHTS set-up of drums at `points` ((mu, Crr) each) from the engine's settled states
    (per drum: positions in the drum frame, velocities, angular velocities; DrumSet.run's
    on_settled): packing.data, drum_k.stl, drums.in, drum_liggghts.in."""
    if len(grain.spheres) != 1:
        raise ValueError("the LIGGGHTS peer runs spheres only")
    os.makedirs(folder, exist_ok=True)
    n_d = len(points)
    centres = drum_centres(n_d)
    lo = centres.min(axis=0) - R_DRUM - 0.01
    hi = centres.max(axis=0) + R_DRUM + 0.01
    with open(os.path.join(folder, "packing.data"), "w") as out:
        total = sum(len(st[0]) for st in states)
        out.write(f"drum packing\n\n{total} atoms\n{2 * n_d} atom types\n\n{lo[0]:.6g} {hi[0]:.6g} xlo xhi\n"
                  f"{-depth / 2 - 0.01:.6g} {depth / 2 + 0.01:.6g} ylo yhi\n"
                  f"{lo[2]:.6g} {hi[2]:.6g} zlo zhi\n\nAtoms\n\n")
        i = 0
        for k, (pos, _, _) in enumerate(states):
            for x in pos + centres[k]:
                i += 1
                out.write(f"{i} {k + 1} {2 * grain.radius} {grain.rho} {x[0]:.9g} {x[1]:.9g} {x[2]:.9g}\n")
        out.write("\nVelocities\n\n")
        i = 0
        for pos, vel, omega in states:
            for v, w in zip(vel, omega):
                i += 1
                out.write(f"{i} {v[0]:.7g} {v[1]:.7g} {v[2]:.7g} {w[0]:.7g} {w[1]:.7g} {w[2]:.7g}\n")
    nt = 2 * n_d  # types 1..n: the grains of drum k; n+1..2n: its walls

    def pair_matrix(grains, walls, other):  # grains(k): drum k's grains among themselves
        m = np.full((nt, nt), float(other))
        for k in range(n_d):
            g, w = k, n_d + k
            m[g, g] = grains(k)
            m[g, w] = m[w, g] = walls
        return f"{nt} " + " ".join(f"{v:.6g}" for v in m.ravel())

    young_types = " ".join([f"{young:g}"] * n_d + [f"{WALL_E:g}"] * n_d)
    nu_types = " ".join([f"{NU:g}"] * n_d + [f"{WALL_NU:g}"] * n_d)
    lines = [f"fix m1 all property/global youngsModulus peratomtype {young_types}",
             f"fix m2 all property/global poissonsRatio peratomtype {nu_types}",
             "fix m3 all property/global coefficientRestitution peratomtypepair "
             + pair_matrix(lambda k: COR, WALL_PAIR["CoR"], COR),
             "fix m4 all property/global coefficientFriction peratomtypepair "
             + pair_matrix(lambda k: points[k][0], WALL_PAIR["mu"], 0.0),
             "fix m5 all property/global coefficientRollingFriction peratomtypepair "
             + pair_matrix(lambda k: points[k][1], WALL_PAIR["Crr"], 0.0)]
    period = 60.0 / RPM
    names = []
    for k in range(n_d):
        drum_stl(os.path.join(folder, f"drum_{k}.stl"), centres[k], depth)
        lines.append(f"fix cad{k} all mesh/surface file drum_{k}.stl type {n_d + k + 1}")
        lines.append(f"fix rot{k} all move/mesh mesh cad{k} rotate origin {centres[k][0]:.9g} 0 {centres[k][2]:.9g} "
                     f"axis 0 1 0 period {period:.9g}")
        names.append(f"cad{k}")
    lines.append(f"fix walls all wall/gran model hertz tangential history rolling_friction cdt mesh n_meshes {n_d} "
                 f"meshes {' '.join(names)}")
    with open(os.path.join(folder, "drums.in"), "w") as out:
        out.write("\n".join(lines) + "\n")
    shutil.copy(os.path.join(HERE, "drum_liggghts.in"), folder)
    return centres


def start_liggghts(folder, points, dt, t_steady, t_measure, samples=30, processes=1):
    """Starts drum_liggghts.in in `folder` (written by write_peer_files) under mpirun when
    processes > 1; returns a handle for finish_liggghts, or None when LIGGGHTS is not installed."""
    import time
    exe = shutil.which("liggghts")
    if not exe:
        return None
    steady = int(round(t_steady / dt))
    frame = int(round(t_measure / samples / dt))
    cmd = [exe, "-in", "drum_liggghts.in", "-log", "none", "-var", "dt", repr(dt), "-var", "steady", str(steady),
           "-var", "measure", str(frame * samples), "-var", "frame", str(frame)]
    mpirun = shutil.which("mpirun")
    if processes > 1 and mpirun:
        cmd = [mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(processes)] + cmd
    else:
        processes = 1
    for f in os.listdir(folder):
        if f.startswith("dump.") and f.endswith(".txt"):
            os.remove(os.path.join(folder, f))
    log = open(os.path.join(folder, "liggghts.out"), "w")
    proc = subprocess.Popen(cmd, cwd=folder, stdout=log, stderr=subprocess.STDOUT, text=True)
    return {"proc": proc, "log": log, "folder": folder, "points": list(points), "steady": steady,
            "frame": frame, "samples": samples, "started": time.time(), "processes": processes}


def finish_liggghts(handle, grain, depth, timeout=7200):
    """Waits for a LIGGGHTS run; returns (angles (n_drums, samples), wall seconds, processes)."""
    import time
    proc = handle["proc"]
    try:
        rc = proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        raise RuntimeError(f"LIGGGHTS ran past {timeout} s")
    wall = time.time() - handle["started"]
    handle["log"].close()
    folder = handle["folder"]
    if rc != 0:
        with open(os.path.join(folder, "liggghts.out"), errors="replace") as f:
            raise RuntimeError(f"LIGGGHTS exited with status {rc}:\n" + f.read()[-4000:])
    points = handle["points"]
    centres = drum_centres(len(points))
    angles = np.full((len(points), handle["samples"]), np.nan)
    for s in range(handle["samples"]):
        step = handle["steady"] + (s + 1) * handle["frame"]
        data = read_dump(os.path.join(folder, f"dump.{step}.txt"))
        for k in range(len(points)):
            pos = data[data[:, 1] == k + 1][:, 2:5] - centres[k]
            angles[k, s] = surface_angle(pos, grain, depth)
    return angles, wall, handle["processes"]


def read_dump(path):
    """(id, type, x, y, z) rows of a LIGGGHTS custom dump."""
    with open(path) as f:
        lines = f.readlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS")) + 1
    return np.loadtxt(lines[start:], ndmin=2)
