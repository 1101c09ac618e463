"""A flat-bottomed cylindrical silo with a circular orifice in the middle of its floor: the geometry
Beverloo's law was fitted to (Beverloo, Leniger & van de Velde 1961, Chem. Eng. Sci. 15, 260), for the
hopper case.

The silo: a cylinder of the grains' material (an analytical wall), a floor of their material (a mesh:
a disc with a circular hole of `orifice` diameter, 96 sides), and a plate under the hole (family 2)
while the grains settle. The grains of the paper's hopper test ID 1 (s. 6.2.2; validation/
hopper_setup.py): plastic spheres PS, r = 3 mm, rho = 1592 kg/m^3, E = 10 MPa, nu = 0.35, CoR = 0.85,
mu = 0.40, Crr = 0.04, dt = 20 us. Grains 5 cm below the floor leave the domain and are removed.
"""
import math

import numpy as np

import hopper_setup as hs
from settling import step_until_still

SIDES = 96
GATE = 2  # as hopper_setup's gate, which hopper_setup.discharge opens


def floor_mesh(hole_radius, outer_radius):
    """A flat annulus at z = 0 facing +z: vertices on the hole's edge and on a circle past the wall."""
    a = np.linspace(0.0, 2.0 * math.pi, SIDES, endpoint=False)
    inner = [[hole_radius * math.cos(t), hole_radius * math.sin(t), 0.0] for t in a]
    outer = [[outer_radius * math.cos(t), outer_radius * math.sin(t), 0.0] for t in a]
    faces = []
    for i in range(SIDES):
        j = (i + 1) % SIDES
        # Counter-clockwise seen from above, so the normal points up.
        faces += [[i, SIDES + i, SIDES + j], [i, SIDES + j, j]]
    return inner + outer, faces


class Silo:
    """n grains poured into a silo of `diameter` with an orifice of `orifice` diameter (m)."""

    def __init__(self, deme, n, diameter, orifice, seed=5):
        self.n, self.diameter, self.orifice = n, diameter, orifice
        sim = self.sim = deme.DEMSolver()
        sim.SetVerbosity("WARNING")
        mat = sim.LoadMaterial({"E": 1e7, "nu": 0.35, "CoR": 0.85, "mu": 0.40, "Crr": 0.04})
        rs = 0.5 * diameter
        # The cloud: a square lattice of 6.6 mm inside the cylinder, each point moved by up to 0.3 mm.
        rng = np.random.default_rng(seed)
        spacing = 2.2 * hs.R
        g = np.arange(-rs + hs.R * 1.2, rs - hs.R * 1.2, spacing)
        X, Y = np.meshgrid(g, g, indexing="ij")
        keep = np.hypot(X, Y) < rs - 1.2 * hs.R
        layer = np.stack([X[keep], Y[keep]], axis=1)
        layers = math.ceil(n / len(layer))
        pts = np.concatenate([np.column_stack([layer, np.full(len(layer), hs.R * 1.2 + k * spacing)])
                              for k in range(layers)])[:n]
        pts[:, :2] += rng.uniform(-3e-4, 3e-4, (n, 2))
        top = float(pts[:, 2].max()) + 2 * spacing
        sim.InstructBoxDomainDimension((-rs - 0.01, rs + 0.01), (-rs - 0.01, rs + 0.01), (-0.05, top))
        sim.SetDomainExitPolicy("remove")
        wall = sim.AddExternalObject()
        wall.AddCylinder([0, 0, 0], [0, 0, 1], rs, mat, 0)
        v, f = floor_mesh(0.5 * orifice, rs + 0.005)
        sim.AddWavefrontMeshObject(deme.DEMMeshConnected(v, f, mat))
        gate = sim.AddExternalObject()
        gate.AddPlane([0, 0, 0], [0, 0, 1], mat)
        gate.SetFamily(GATE)
        self.grains = sim.AddClumps(sim.LoadSphereType(hs.MASS, hs.R, mat), pts)
        sim.SetInitTimeStep(hs.DT)
        sim.SetGravitationalAcceleration([0, 0, -hs.G])
        sim.Initialize()
        self.tracker = sim.Track(self.grains)

    def settle(self, t_min=0.3, t_max=2.0, v_mean=5e-3, frame=0.05):
        """Lets the cloud settle on the closed orifice until the grains' mean speed is below v_mean;
        returns the time it took."""
        return step_until_still(self.sim, self.tracker, t_min, t_max, v_mean, frame=frame)[0]

    def measure(self):
        """The settled bed: its fill height (m: the median top of its highest 3 % of grains) and its
        bulk density (kg/m^3: the grains whose centres lie in the cylinder from 2 cm above the floor
        to 2 cm below the fill height, 1.5 cm or more from the wall, over that cylinder's volume)."""
        p = np.asarray(self.tracker.Positions())
        r_xy = np.hypot(p[:, 0], p[:, 1])
        tops = p[:, 2] + hs.R
        self.fill = float(np.median(tops[tops > np.percentile(tops, 97)]))
        lo, hi, rr = 0.02, self.fill - 0.02, 0.5 * self.diameter - 0.015
        inside = (p[:, 2] > lo) & (p[:, 2] < hi) & (r_xy < rr)
        self.rho_bulk = hs.MASS * np.count_nonzero(inside) / (math.pi * rr ** 2 * (hi - lo))
        return self.fill, self.rho_bulk

    def discharge(self, t_end, stop_fraction=0.999, frame=0.05):
        """Opens the orifice; returns (times, discharged mass fractions) every frame until t_end or
        until `stop_fraction` of the grains' mass has left."""
        return hs.discharge(self.sim, self.n, t_end, frame, stop_fraction=stop_fraction)


def beverloo(rho_bulk, orifice, c=0.58, k=1.5):
    """Beverloo et al. (1961): W = C rho_bulk sqrt(g) (D0 - k d)^(5/2), kg/s."""
    return c * rho_bulk * math.sqrt(hs.G) * (orifice - k * 2 * hs.R) ** 2.5
