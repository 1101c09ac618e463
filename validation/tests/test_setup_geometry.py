"""The geometry helpers of the silo and repose measurements, without a simulation: the silo's floor
is an annulus facing up with a hole of the orifice's size, and the heap's angle is read back from a
made-up heap of known slope."""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import repose  # noqa: E402
import silo_setup  # noqa: E402


def test_silo_floor_is_an_annulus_facing_up():
    v, f = silo_setup.floor_mesh(0.02, 0.085)
    v, f = np.array(v), np.array(f)
    assert np.all(v[:, 2] == 0.0)
    radii = np.hypot(v[:, 0], v[:, 1])
    assert np.allclose(radii[:silo_setup.SIDES], 0.02) and np.allclose(radii[silo_setup.SIDES:], 0.085)
    normals = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    assert np.all(normals[:, 2] > 0) and np.allclose(normals[:, :2], 0.0, atol=1e-12)
    # The triangles tile the polygonal annulus: area 0.5 N sin(2 pi / N) (R^2 - r^2).
    area = 0.5 * float(np.sum(normals[:, 2]))
    n = silo_setup.SIDES
    assert math.isclose(area, 0.5 * n * math.sin(2 * math.pi / n) * (0.085 ** 2 - 0.02 ** 2), rel_tol=1e-9)


def test_heap_angle_of_a_made_up_wedge():
    # Grains of r = 1.5 mm filling a wedge at 20 degrees (plateau 2 cm, slope down to a 2 mm toe layer).
    rng = np.random.default_rng(1)
    r, slope = 0.0015, math.tan(math.radians(20.0))
    x = rng.uniform(0.0, 0.2, 40000)
    top = np.clip(0.05 - slope * np.maximum(x - 0.02, 0.0), 0.002, None)
    z = rng.uniform(0.0, 1.0, x.size) * top
    p = np.stack([x, np.zeros_like(x), z - r], axis=1)
    angle, se, (xs, zs, w) = repose.surface_angle(p, np.full(x.size, r), 0.006)
    assert abs(angle - 20.0) < 0.5 and se < 0.5
    assert zs[w].max() <= 0.8 * zs.max() + 0.006 * slope and zs[w].min() >= 0.2 * zs.max() - 0.006 * slope
