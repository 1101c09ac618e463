"""The flat-bottomed hopper of the paper's s. 6.2.2 (test ID 1, plastic spheres), shared by the
hopper cases: build it, settle the grains on the closed orifice, open it, record the discharge, and
write the settled packing and the floor for a LIGGGHTS run of the same hopper (hopper_liggghts.in).

Geometry: 0.20 m wide (x), 0.04 m deep (y), walls of the grains' material; a 0.04 x 0.04 m orifice in
the middle of the floor, spanning the depth. Grains: r = 3 mm, rho = 1592 kg/m^3, E = 10 MPa,
nu = 0.35, CoR = 0.85, mu = 0.40, Crr = 0.04, dt = 20 us. Grains that fall 5 cm below the floor are
removed (SetDomainExitPolicy("remove")).
"""
import math
import os
import shutil
import subprocess

import numpy as np

R, RHO, G = 0.003, 1592.0, 9.81
HALF_X, HALF_Y, ORIFICE_HALF = 0.1, 0.02, 0.02
MASS = RHO * 4.0 / 3.0 * math.pi * R ** 3
DT = 2e-5
# The floor: two plates of two triangles each, either side of the orifice, facing +z.
FLOOR_V = [[-HALF_X, -HALF_Y, 0], [-ORIFICE_HALF, -HALF_Y, 0], [-ORIFICE_HALF, HALF_Y, 0], [-HALF_X, HALF_Y, 0],
           [ORIFICE_HALF, -HALF_Y, 0], [HALF_X, -HALF_Y, 0], [HALF_X, HALF_Y, 0], [ORIFICE_HALF, HALF_Y, 0]]
FLOOR_F = [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]]
HERE = os.path.dirname(os.path.abspath(__file__))


def settled_hopper(deme, n, settle_time):
    """A solver with n grains settled on the closed orifice; returns (sim, tracker, positions)."""
    sim = deme.DEMSolver()
    sim.SetVerbosity("WARNING")
    mat = sim.LoadMaterial({"E": 1e7, "nu": 0.35, "CoR": 0.85, "mu": 0.40, "Crr": 0.04})
    sim.InstructBoxDomainDimension((-HALF_X, HALF_X), (-HALF_Y, HALF_Y), (-0.05, 0.56))
    sim.SetDomainExitPolicy("remove")
    sim.AddBCPlane([-HALF_X, 0, 0], [1, 0, 0], mat)
    sim.AddBCPlane([HALF_X, 0, 0], [-1, 0, 0], mat)
    sim.AddBCPlane([0, -HALF_Y, 0], [0, 1, 0], mat)
    sim.AddBCPlane([0, HALF_Y, 0], [0, -1, 0], mat)
    sim.AddWavefrontMeshObject(deme.DEMMeshConnected(FLOOR_V, FLOOR_F, mat))
    # The gate under the orifice while the bed settles: a plane of family 2, whose contacts with the
    # grains are then disabled (open_orifice).
    gate = sim.AddExternalObject()
    gate.AddPlane([0, 0, 0], [0, 0, 1], mat)
    gate.SetFamily(2)
    # A loose grid, 30 x 6 per layer, each grain moved by up to 0.3 mm (so that the layers do not stack).
    rng = np.random.default_rng(3)
    spacing = 0.0066
    layer = [(-0.0957 + i * spacing, -0.0165 + j * spacing) for i in range(30) for j in range(6)]
    pts = [[x + rng.uniform(-3e-4, 3e-4), y + rng.uniform(-3e-4, 3e-4), 0.0035 + k * spacing]
           for k in range(math.ceil(n / len(layer))) for x, y in layer][:n]
    grains = sim.AddClumps(sim.LoadSphereType(MASS, R, mat), pts)
    sim.SetInitTimeStep(DT)
    sim.SetGravitationalAcceleration([0, 0, -G])
    sim.Initialize()
    sim.DoDynamics(settle_time)
    tr = sim.Track(grains)
    return sim, np.array(tr.Positions())


def bulk_density(z):
    """The settled bed's bulk density in a slab away from the floor and the surface."""
    fill = float(np.max(z) + R)
    lo, hi = 0.02, 0.7 * fill
    return fill, MASS * np.count_nonzero((z > lo) & (z < hi)) / (2 * HALF_X * 2 * HALF_Y * (hi - lo))


def discharge(sim, n, t_end, frame=0.05):
    """Opens the orifice and records (times, discharged mass fractions) every frame until t_end or
    until all grains are out."""
    sim.DisableContactBetweenFamilies(0, 2)
    total = n * MASS
    t, m = [0.0], [0.0]
    while t[-1] < t_end - 1e-9 and sim.GetRemovedMass() < 0.999 * total:
        sim.DoDynamics(frame)
        t.append(t[-1] + frame)
        m.append(sim.GetRemovedMass())
    return np.array(t), np.array(m) / total


def steady_rate(t, frac, n):
    """Mass flow rate (kg/s): the slope of the discharged mass between 20 % and 60 % discharged."""
    w = (frac >= 0.2) & (frac <= 0.6)
    if np.count_nonzero(w) < 3:
        return float("nan")
    return float(np.polyfit(t[w], frac[w] * n * MASS, 1)[0])


def beverloo(rho_bulk):
    """Beverloo et al. (1961) with C = 0.58, k = 1.5 and the orifice's hydraulic diameter."""
    d_h = 4 * (2 * ORIFICE_HALF) ** 2 / (4 * 2 * ORIFICE_HALF)
    return 0.58 * rho_bulk * math.sqrt(G) * (d_h - 1.5 * 2 * R) ** 2.5


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
