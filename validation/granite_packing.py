"""A dense random packing of equal spheres for the granite specimen (validation/pending/granite.py with
GRANITE_PACKING=random; validation/README.md, granite), made by the engine.

Scholtes & Donze's specimens are dense random packings, not lattices: their bonds point every way,
so that inclined bonds carry shear whatever the load's direction. Made here as follows (our choices):
- spheres placed at random without overlap (random sequential addition) in a box 1.4 times the
  final one each way (a solid fraction of about 0.23), at rest;
- frictionless, soft (E = 1 GPa, CoR 0.1), pressed by the box's six walls moving inward at a constant
  speed; every `check` steps the walls' mean pressure is read, and once it passes `pressure` the walls
  stop (their families made fixed), or they stop where the final box is;
- left to relax with the walls still until the fastest sphere is below 1 mm/s;
- the spheres touching a z wall set at one radius from it (flat end faces);
- the specimen is the spheres whose centres lie within the specimen's box in x and y (the rows next
  to the x and y walls cut off: a wall orders the spheres next to it), all of them in z (its plates
  stand where the z walls stood).
Returns the centres (an N x 3 array), the solid fraction inside the specimen's box and the walls'
final pressure.
"""
import itertools
import math

import numpy as np


def random_sequential(rng, lo, hi, radius, count, tries_per_sphere=2000):
    """`count` centres in the box [lo, hi] (centres at least a radius from each face) with no two closer
    than two radii, placed one after the other at random (a cell grid of one diameter finds the
    neighbours)."""
    lo, hi = np.asarray(lo, float) + radius, np.asarray(hi, float) - radius
    cell = 2.0 * radius
    dims = np.maximum(1, np.ceil((hi - lo) / cell).astype(int))
    grid = {}
    pts = []
    near = list(itertools.product((-1, 0, 1), repeat=3))

    def overlaps(p, c):
        return any(np.sum((p - q) ** 2) < cell * cell for d in near
                   for q in grid.get((c[0] + d[0], c[1] + d[1], c[2] + d[2]), ()))

    for attempt in range(tries_per_sphere * count):
        if len(pts) == count:
            break
        p = lo + rng.random(3) * (hi - lo)
        c = tuple(np.minimum(((p - lo) / cell).astype(int), dims - 1))
        if not overlaps(p, c):
            pts.append(p)
            grid.setdefault(c, []).append(p)
    if len(pts) < count:
        raise RuntimeError(f"random_sequential: placed {len(pts)} of {count} spheres")
    return np.array(pts)


def random_packing(deme, half, radius, density, seed=1, margin_diameters=2.0, fraction=0.64, growth=1.4,
                   pressure=5e5, check=200, log=None):
    """The packing for a specimen of half sizes `half`: see the module's text. The packed box is the
    specimen's widened by `margin_diameters` each way in x and y; it holds spheres for `fraction` of
    its volume."""
    d = 2.0 * radius
    final = np.array([half[0] + margin_diameters * d, half[1] + margin_diameters * d, half[2]])
    vol_sphere = 4.0 / 3.0 * math.pi * radius ** 3
    count = int(fraction * np.prod(2.0 * final) / vol_sphere)
    start = final * growth
    rng = np.random.default_rng(seed)
    pts = random_sequential(rng, -start, start, radius, count)

    sim = deme.DEMSolver()
    sim.SetVerbosity("ERROR")
    mat = sim.LoadMaterial({"E": 1e9, "nu": 0.3, "CoR": 0.1, "mu": 0.0})
    span = 4.0 * float(start.max())
    sim.InstructBoxDomainDimension(span, span, span)
    mass = density * vol_sphere
    grains = sim.AddClumps(sim.LoadSphereType(mass, radius, mat), pts)
    # Six walls, each in a family of its own that moves it inward so that all reach the final box at
    # once (t_press), then a fixed family.
    t_press = 2e-2
    walls = []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            fam = 1 + len(walls)
            origin = [0.0, 0.0, 0.0]
            origin[axis] = sign * start[axis]
            normal = [0.0, 0.0, 0.0]
            normal[axis] = -sign
            w = sim.AddBCPlane(origin, normal, mat)
            w.SetFamily(fam)
            v = ["0", "0", "0"]
            v[axis] = repr(-sign * (start[axis] - final[axis]) / t_press)
            sim.SetFamilyPrescribedLinVel(fam, *v)
            walls.append((w, axis, sign))
    sim.SetFamilyFixed(10)
    sim.SetGravitationalAcceleration([0, 0, 0])
    # The Rayleigh time of the soft spheres, a tenth of it a step.
    g = 1e9 / (2 * 1.3)
    dt = 0.1 * math.pi * radius * math.sqrt(density / g) / (0.1631 * 0.3 + 0.8766)
    sim.SetInitTimeStep(dt)
    sim.Initialize()
    trackers = [(sim.Track(w), axis) for w, axis, _ in walls]
    tr = sim.Track(grains)

    def box_half(time):  # the walls' half-distances (they all move in step)
        return start - (start - final) * min(time / t_press, 1.0)

    def wall_pressure(time):
        box = box_half(time)
        total = 0.0
        for t, axis in trackers:
            other = [2.0 * box[b] for b in range(3) if b != axis]
            total += abs(t.ContactForce()[axis]) / (other[0] * other[1])
        return total / 6.0

    steps = 0
    moving = True
    p = 0.0
    while moving:
        sim.DoDynamics(check * dt)
        steps += check
        p = wall_pressure(steps * dt)
        if p >= pressure or steps * dt >= t_press:
            for fam in range(1, 7):
                sim.ChangeFamily(fam, 10)
            moving = False
    stopped = box_half(steps * dt)
    # Relax with the walls still (the pressure is read at the stopped box).
    for _ in range(200):
        sim.DoDynamics(check * dt)
        vmax = max(np.linalg.norm(tr.Vel(i)) for i in range(0, len(pts), max(1, len(pts) // 500)))
        if vmax < 1e-3:
            break
    p = wall_pressure(steps * dt)
    centres = np.array([tr.Pos(i) for i in range(len(pts))], dtype=np.float64)
    z_lo, z_hi = -stopped[2], stopped[2]
    # The spheres that touch a z wall are set at one radius from it: their overlaps with the soft
    # wall (up to some tens of um) would leave the specimen's end faces rough on the scale of the
    # plates' travel to the peak (a stiff plate would meet one sphere first). A shift of a few
    # hundredths of a radius; the bonds take the pairs as they are then as their rest state.
    centres[:, 2] = np.where(centres[:, 2] < z_lo + radius, z_lo + radius, centres[:, 2])
    centres[:, 2] = np.where(centres[:, 2] > z_hi - radius, z_hi - radius, centres[:, 2])
    inside = (np.abs(centres[:, 0]) <= half[0]) & (np.abs(centres[:, 1]) <= half[1])
    kept = centres[inside]
    # Solid fraction: the kept spheres' volume over the specimen's x-y box between the z walls (the
    # box their centres were taken from, so that as much of the kept spheres' volume sticks out of
    # it at its cut sides as the cut-off spheres' reaches in).
    solid = len(kept) * vol_sphere / (4.0 * half[0] * half[1] * (z_hi - z_lo))
    if log:
        log(f"random packing: {len(pts)} spheres pressed for {steps} steps to {p / 1e6:.2f} MPa; "
            f"{len(kept)} kept, solid fraction {solid:.3f}")
    return kept, solid, p
