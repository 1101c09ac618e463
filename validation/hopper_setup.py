"""The flat-bottomed hopper of the paper's s. 6.2.2 (test IDs 1, plastic spheres, and 2, wooden
cylinders), shared by the hopper cases: build it, settle the grains on the closed orifice, open it,
record the discharge, and write the settled packing and the floor for a LIGGGHTS run of the same
hopper (hopper_liggghts.in).

Geometry: 0.20 m wide (x), 0.04 m deep (y), walls of the grains' material; a 0.04 x 0.04 m orifice in
the middle of the floor, spanning the depth. Test ID 1's grains: r = 3 mm, rho = 1592 kg/m^3, E = 10 MPa,
nu = 0.35, CoR = 0.85, mu = 0.40, Crr = 0.04, dt = 20 us (test ID 2's: settled_cylinder_hopper).
Grains that fall 5 cm below the floor are removed (SetDomainExitPolicy("remove")).
"""
import math
import os
import shutil
import subprocess

import numpy as np

from drum_setup import Grain

R, RHO, G = 0.003, 1592.0, 9.81
HALF_X, HALF_Y, ORIFICE_HALF = 0.1, 0.02, 0.02
MASS = RHO * 4.0 / 3.0 * math.pi * R ** 3
DT = 2e-5
# The floor: two plates of two triangles each, either side of the orifice, facing +z.
FLOOR_V = [[-HALF_X, -HALF_Y, 0], [-ORIFICE_HALF, -HALF_Y, 0], [-ORIFICE_HALF, HALF_Y, 0], [-HALF_X, HALF_Y, 0],
           [ORIFICE_HALF, -HALF_Y, 0], [HALF_X, -HALF_Y, 0], [HALF_X, HALF_Y, 0], [ORIFICE_HALF, HALF_Y, 0]]
FLOOR_F = [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]]
HERE = os.path.dirname(os.path.abspath(__file__))


def _hopper(deme, material, grain_top):
    """A solver holding the hopper's walls, floor and closed gate, of the grains' material (a dict)."""
    sim = deme.DEMSolver()
    sim.SetVerbosity("WARNING")
    mat = sim.LoadMaterial(material)
    sim.InstructBoxDomainDimension((-HALF_X, HALF_X), (-HALF_Y, HALF_Y), (-0.05, max(0.56, grain_top + 0.01)))
    sim.SetDomainExitPolicy("remove")
    sim.AddBCPlane([-HALF_X, 0, 0], [1, 0, 0], mat)
    sim.AddBCPlane([HALF_X, 0, 0], [-1, 0, 0], mat)
    sim.AddBCPlane([0, -HALF_Y, 0], [0, 1, 0], mat)
    sim.AddBCPlane([0, HALF_Y, 0], [0, -1, 0], mat)
    sim.AddWavefrontMeshObject(deme.DEMMeshConnected(FLOOR_V, FLOOR_F, mat))
    # The gate under the orifice while the bed settles: a plane of family 2, whose contacts with the
    # grains are then disabled (discharge).
    gate = sim.AddExternalObject()
    gate.AddPlane([0, 0, 0], [0, 0, 1], mat)
    gate.SetFamily(2)
    return sim, mat


def _settle(sim, grains, settle_time, dt=DT):
    sim.SetInitTimeStep(dt)
    sim.SetGravitationalAcceleration([0, 0, -G])
    sim.Initialize()
    sim.DoDynamics(settle_time)
    return np.array(sim.Track(grains).Positions())


def settled_hopper(deme, n, settle_time):
    """The paper's test ID 1: a solver with n plastic spheres settled on the closed orifice; returns
    (sim, positions)."""
    # A loose grid, 30 x 6 per layer, each grain moved by up to 0.3 mm (so that the layers do not stack).
    rng = np.random.default_rng(3)
    spacing = 0.0066
    layer = [(-0.0957 + i * spacing, -0.0165 + j * spacing) for i in range(30) for j in range(6)]
    pts = [[x + rng.uniform(-3e-4, 3e-4), y + rng.uniform(-3e-4, 3e-4), 0.0035 + k * spacing]
           for k in range(math.ceil(n / len(layer))) for x, y in layer][:n]
    sim, mat = _hopper(deme, {"E": 1e7, "nu": 0.35, "CoR": 0.85, "mu": 0.40, "Crr": 0.04}, max(p[2] for p in pts))
    grains = sim.AddClumps(sim.LoadSphereType(MASS, R, mat), pts)
    return sim, _settle(sim, grains, settle_time)


# The paper's test ID 2: wooden "cylinders" WC (its particle table: r = 2 mm, 8.5 mm long, 476 kg/m^3,
# E = 10 MPa, nu = 0.35, CoR = 0.55; mu = 0.70 and Crr = 0.07 in its hopper table) as five spheres
# of r = 2 mm on the axis, the end ones touching the ends, with a solid cylinder's mass and inertia.
WC_R, WC_LENGTH = 0.002, 0.0085
WC = Grain("WC", WC_R, 476.0, [[x, 0.0, 0.0] for x in np.linspace(-(WC_LENGTH / 2 - WC_R), WC_LENGTH / 2 - WC_R, 5)],
           per_metre=0.0)
WC_MASS = WC.mass
WC_DT = 1e-5  # 13 % of a component sphere's Rayleigh time (20 us, the spheres' step, would be 26 %)


def settled_cylinder_hopper(deme, n, settle_time, seed=3):
    """The paper's test ID 2: a solver with n wooden cylinders settled on the closed orifice; returns
    (sim, positions). Poured as 2 x 2 bundles of parallel clumps filling cubes of the length plus
    0.4 mm, each cube's axis x, y or z at random, each clump moved by up to 0.08 mm."""
    rng = np.random.default_rng(seed)
    c = WC_LENGTH + 0.4e-3
    nx, ny = int(2 * HALF_X / c), int(2 * HALF_Y / c)
    cubes = math.ceil(n / 4)
    layers = math.ceil(cubes / (nx * ny))
    k, i, j = np.meshgrid(np.arange(layers), np.arange(nx), np.arange(ny), indexing="ij")
    centre = np.stack([-HALF_X + (i.ravel() + 0.5) * 2 * HALF_X / nx, -HALF_Y + (j.ravel() + 0.5) * 2 * HALF_Y / ny,
                       0.5e-3 + (k.ravel() + 0.5) * c], axis=1)[:cubes]
    # The clump's axis is its frame's x: a cube along y turns it 90 degrees about z, along z -90 about y.
    h = math.sqrt(0.5)
    quats = {0: [0.0, 0.0, 0.0, 1.0], 1: [0.0, 0.0, h, h], 2: [0.0, -h, 0.0, h]}
    across = {0: (1, 2), 1: (0, 2), 2: (0, 1)}
    pts, oris = [], []
    for ctr, axis in zip(centre, rng.integers(0, 3, len(centre))):
        a, b = across[int(axis)]
        for da, db in ((-1, -1), (-1, 1), (1, -1), (1, 1)):
            p = ctr.copy()
            p[a] += da * c / 4
            p[b] += db * c / 4
            pts.append(p + rng.uniform(-8e-5, 8e-5, 3))
            oris.append(quats[int(axis)])
    pts, oris = np.array(pts[:n]), np.array(oris[:n])
    material = {"E": 1e7, "nu": 0.35, "CoR": 0.55, "mu": 0.70, "Crr": 0.07}
    sim, mat = _hopper(deme, material, float(pts[:, 2].max()) + c)
    tmpl = sim.LoadClumpType(WC.mass, WC.moi, [WC_R] * len(WC.spheres), WC.spheres.tolist(), mat)
    grains = sim.AddClumps(tmpl, pts)
    grains.SetOriQ(oris)
    return sim, _settle(sim, grains, settle_time, WC_DT)


def bulk_density(z):
    """The settled bed's bulk density in a slab away from the floor and the surface."""
    fill = float(np.max(z) + R)
    lo, hi = 0.02, 0.7 * fill
    return fill, MASS * np.count_nonzero((z > lo) & (z < hi)) / (2 * HALF_X * 2 * HALF_Y * (hi - lo))


def discharge(sim, n, t_end, frame=0.05, grain_mass=MASS, stop_fraction=0.999, on_frame=None):
    """Opens the orifice (the gate of family 2 lets the grains through) and records (times, discharged
    mass fractions) every frame until t_end or until `stop_fraction` of the grains' mass is out;
    on_frame(times, fractions), if given, sees the curve so far after every frame."""
    sim.DisableContactBetweenFamilies(0, 2)
    total = n * grain_mass
    t, m = [0.0], [0.0]
    while t[-1] < t_end - 1e-9 and sim.GetRemovedMass() < stop_fraction * total:
        sim.DoDynamics(frame)
        t.append(t[-1] + frame)
        m.append(sim.GetRemovedMass())
        if on_frame:
            on_frame(t, [x / total for x in m])
    return np.array(t), np.array(m) / total


def steady_rate(t, frac, n, grain_mass=MASS):
    """Mass flow rate (kg/s): the slope of the discharged mass between 20 % and 60 % discharged."""
    w = (frac >= 0.2) & (frac <= 0.6)
    if np.count_nonzero(w) < 3:
        return float("nan")
    return float(np.polyfit(t[w], frac[w] * n * grain_mass, 1)[0])


def write_peer_files(folder, positions):
    """The settled packing (LIGGGHTS data file, grains of type 1, walls of type 2) and the floor (STL)."""
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "packing.data"), "w") as out:
        out.write(f"hopper packing\n\n{len(positions)} atoms\n2 atom types\n\n{-HALF_X} {HALF_X} xlo xhi\n"
                  f"{-HALF_Y} {HALF_Y} ylo yhi\n-0.05 0.56 zlo zhi\n\nAtoms\n\n")
        for k, x in enumerate(positions):
            out.write(f"{k + 1} 1 {2 * R} {RHO} {x[0]:.9g} {x[1]:.9g} {x[2]:.9g}\n")
    with open(os.path.join(folder, "floor.stl"), "w") as out:
        out.write("solid floor\n")
        for tri in FLOOR_F:
            out.write("facet normal 0 0 1\nouter loop\n")
            for i in tri:
                out.write(f"vertex {FLOOR_V[i][0]} {FLOOR_V[i][1]} {FLOOR_V[i][2]}\n")
            out.write("endloop\nendfacet\n")
        out.write("endsolid floor\n")
    shutil.copy(os.path.join(HERE, "hopper_liggghts.in"), folder)


def run_liggghts(folder, n, t_end):
    """Runs hopper_liggghts.in in `folder` for t_end seconds; returns (times, discharged fractions).
    The case checks first that LIGGGHTS is installed (Case.require_liggghts)."""
    exe = shutil.which("liggghts")
    steps = int(round(t_end / DT))
    cmd = [exe, "-in", "hopper_liggghts.in", "-log", "none", "-var", "steps", str(steps)]
    mpirun = shutil.which("mpirun")
    if mpirun and (os.cpu_count() or 1) >= 2 and os.environ.get("OMP_NUM_THREADS") != "1":
        cmd = [mpirun, "--allow-run-as-root", "-np", "2"] + cmd
    out = subprocess.run(cmd, cwd=folder, capture_output=True, text=True, timeout=7200)
    if out.returncode != 0:
        raise SystemExit("LIGGGHTS failed:\n" + out.stdout[-3000:] + out.stderr[-3000:])
    t, left = [], []
    for line in out.stdout.splitlines():
        p = line.split()
        if len(p) == 3 and p[0].isdigit():
            try:
                t.append(float(p[1]))
                left.append(int(p[2]))
            except ValueError:
                pass
    return np.array(t), (n - np.array(left)) / n
