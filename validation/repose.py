"""The angle of repose of a granular material: a heap left by a collapsing column (a dam break).

Grains settle into a column against the wall x = 0, held at x = `width` by a gate; the gate opens, the
column slumps into a heap and, once every grain is still, the heap's free surface is measured. The
period along y makes the heap a long ridge with no side walls (so no wall friction props it up); with
`rough_floor` the floor is a layer of fixed grains (on a flat floor, spheres without rolling
resistance roll out from under the heap: the crater's grains gave 8.5 degrees so, 17.0-17.6 on the
rough floor). The angle: a least-squares line through the heap's surface heights (the top of the
highest grain in each strip of two largest diameters along x) from below the crest (80 % of the
heap's height) to above the toe (20 %). It is the static angle a heap keeps at rest after flowing.
"""
import math

import numpy as np

from settling import step_until_still

GATE = 2  # the gate's family
FLOOR = 3  # the fixed grains of a rough floor


class Heap:
    """A column of grains of the given radii (m, each equally likely) and material, `width` x `period`
    (x, y) and about `height` tall, on a floor of their material."""

    def __init__(self, deme, radii, rho, material, width, period, height, dt, seed=1, rough_floor=False):
        self.width, self.height, self.radii = width, height, np.asarray(radii, float)
        sim = self.sim = deme.DEMSolver()
        sim.SetVerbosity("WARNING")
        mat = sim.LoadMaterial(material)
        sim.InstructBoxDomainPeriodicity("y")
        sim.AddBCPlane([0, 0, 0], [0, 0, 1], mat)
        sim.AddBCPlane([0, 0, 0], [1, 0, 0], mat)
        gate = sim.AddExternalObject()
        gate.AddPlane([width, 0, 0], [-1, 0, 0], mat)
        gate.SetFamily(GATE)
        types = [sim.LoadSphereType(rho * 4.0 / 3.0 * math.pi * r ** 3, float(r), mat) for r in self.radii]
        # A loose lattice just over the largest diameter, each point moved a little, falling.
        rng = np.random.default_rng(seed)
        a = 2.0 * float(self.radii.max()) * 1.03
        nx, ny = int(width / a), int(period / a)
        mean_vol = float(np.mean(4.0 / 3.0 * math.pi * self.radii ** 3))
        n = int(0.6 * width * period * height / mean_vol)
        layers = math.ceil(n / (nx * ny))
        k, i, j = np.meshgrid(np.arange(layers), np.arange(nx), np.arange(ny), indexing="ij")
        pts = np.stack([(i.ravel() + 0.5) * width / nx, (j.ravel() + 0.5) * period / ny,
                        (k.ravel() + 0.5) * a + 1e-4 + (float(self.radii.max()) if rough_floor else 0.0)], axis=1)[:n]
        pts += rng.uniform(-0.05 * a, 0.05 * a, pts.shape)
        # Room for the heap's toe, closed by a far wall: spheres without rolling resistance roll on
        # along the floor until a wall stops them.
        end = width + 4.0 * height
        top = max(2.2 * height, float(pts[:, 2].max()) + a)
        sim.InstructBoxDomainDimension((0.0, end), (0.0, period), (0.0, top))
        sim.AddBCPlane([end, 0, 0], [-1, 0, 0], mat)
        kind = rng.integers(0, len(self.radii), len(pts))
        self.r = self.radii[kind]
        grains = sim.AddClumps([types[q] for q in kind], pts)
        if rough_floor:
            # A floor of fixed grains, the largest size on a square lattice just over its diameter.
            b = 2.0 * float(self.radii.max()) * 1.02
            fx, fy = np.meshgrid(np.arange(0.5 * b, end, b), np.arange(0.5 * b, period - 0.25 * b, b), indexing="ij")
            floor = sim.AddClumps(types[-1], np.stack([fx.ravel(), fy.ravel(), np.zeros(fx.size)], axis=1))
            floor.SetFamily(FLOOR)
            sim.SetFamilyFixed(FLOOR)
        sim.SetInitTimeStep(dt)
        sim.SetGravitationalAcceleration([0.0, 0.0, -9.81])
        sim.SetErrorOutVelocity(20.0)
        sim.Initialize()
        self.tracker = sim.Track(grains)
        self.n = len(pts)

    def run_until_still(self, t_min, t_max, v_mean=1e-3, v_max=0.02, frame=0.02):
        """Steps until the grains are still (settling.step_until_still); returns the time it took and
        whether they came to rest."""
        return step_until_still(self.sim, self.tracker, t_min, t_max, v_mean, v_max, frame)[:2]

    def open_gate(self):
        self.sim.DisableContactBetweenFamilies(0, GATE)

    def angle(self):
        """The heap's angle of repose (degrees), its standard error and the profile (surface_angle)."""
        return surface_angle(np.asarray(self.tracker.Positions()), self.r, 4.0 * float(self.radii.max()))


def surface_angle(p, r, strip):
    """The angle (degrees) of a heap's slope falling along +x, and its standard error (degrees), from
    the grains' centres p (n, 3) and radii r: the top of the highest grain in each strip of width
    `strip` along x, a least-squares line through the strips from just below the crest (the last strip
    above 80 % of the highest top) to just above the toe (the first strip after it below 20 %).
    Also returns the profile (strip centres, tops, the indices fitted)."""
    ix = np.floor(p[:, 0] / strip).astype(int)
    tops = {}
    for i, z in zip(ix, p[:, 2] + r):
        tops[i] = max(z, tops.get(i, 0.0))
    xs = np.array([(i + 0.5) * strip for i in sorted(tops)])
    zs = np.array([tops[i] for i in sorted(tops)])
    peak = float(zs.max())
    crest = int(np.nonzero(zs > 0.8 * peak)[0].max())
    toe = crest + int(np.argmax(zs[crest:] < 0.2 * peak))
    w = np.arange(crest + 1, toe)
    if len(w) < 3:
        raise RuntimeError(f"the heap's slope spans {len(w)} strips: too few to fit")
    (slope, _), cov = np.polyfit(xs[w], zs[w], 1, cov=True)
    se = math.degrees(math.sqrt(cov[0, 0]) / (1.0 + slope ** 2))
    return math.degrees(math.atan(-slope)), se, (xs, zs, w)


def crater_grains_angle(deme, seed=1, period=0.02):
    """The angle of repose (degrees, its standard error) of the crater case's grains (crater_setup),
    from a column 6 cm wide and 5 cm tall on a rough floor."""
    import crater_setup as cs
    material = {"E": cs.E, "nu": cs.NU, "CoR": cs.COR, "mu": cs.MU, "Crr": 0.0}
    dt = 0.1 * deme.RayleighTime(float(cs.RADII[0]), cs.RHO_GRAIN, cs.E, cs.NU)
    heap = Heap(deme, cs.RADII, cs.RHO_GRAIN, material, 0.06, period, 0.05, dt, seed=seed, rough_floor=True)
    heap.run_until_still(0.15, 1.0)
    heap.open_gate()
    _, still = heap.run_until_still(0.3, 3.0)
    if not still:
        raise RuntimeError("the heap did not come to rest within 3 s")
    angle, se, _ = heap.angle()
    return angle, se, heap.n


if __name__ == "__main__":
    # python3 validation/repose.py [seed] [period]: the crater grains' angle of repose (validation/README.md).
    import sys
    from common import import_deme
    seed = int(sys.argv[1]) if len(sys.argv) > 1 else 1
    period = float(sys.argv[2]) if len(sys.argv) > 2 else 0.02
    a, se, n = crater_grains_angle(import_deme(), seed, period)
    print(f"crater grains: angle of repose {a:.2f} +- {se:.2f} degrees (tan {math.tan(math.radians(a)):.3f}), "
          f"{n} grains, seed {seed}, period {period} m")
