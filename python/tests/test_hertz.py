"""A Hertz impact driven from Python, against the analytical contact time.

Hertz theory (K. L. Johnson, Contact Mechanics, Cambridge 1985, §11.4, eq. 11.24): a sphere of
mass m and radius R hitting a flat at speed v, with effective modulus E* (1/E* = (1 - nu1^2)/E1
+ (1 - nu2^2)/E2, here both sides of one material: E* = E / (2 (1 - nu^2))) and effective mass
m* = m (the plane does not move), stays in contact for
    t_c = 2.868 (m*^2 / (R E*^2 v))^(1/5)
and reaches the peak overlap delta_max = (15 m* v^2 / (16 E* sqrt(R)))^(2/5).
With CoR = 1 the model has no damping. Tolerance 2 % (the issue's requirement); the step is
t_c / 2000, so counting steps resolves the time to 0.05 %."""
import math

import numpy as np

import deme
from conftest import material, quiet_solver, sphere_mass


def test_contact_time_matches_hertz():
    r, density, E, nu, v = 0.01, 2600.0, 1e8, 0.3, 1.0
    m = sphere_mass(r, density)
    Estar = E / (2 * (1 - nu * nu))
    tc = 2.868 * (m * m / (r * Estar * Estar * v)) ** 0.2
    delta_max = (15 * m * v * v / (16 * Estar * math.sqrt(r))) ** 0.4
    dt = tc / 2000

    sim = quiet_solver()
    mat = material(sim, E=E, nu=nu, CoR=1.0, mu=0.0)
    sim.InstructBoxDomainDimension(1, 1, 1)
    sim.AddBCPlane([0, 0, 0], [0, 0, 1], mat)
    ball_t = sim.LoadSphereType(m, r, mat)
    ball = sim.AddClumps(ball_t, [[0, 0, r + 10 * v * dt]])  # touches the plane after ~10 steps
    ball.SetVel([0, 0, -v])
    sim.SetInitTimeStep(dt)
    sim.SetGravitationalAcceleration([0, 0, 0])
    sim.Initialize()
    tr = sim.Track(ball)

    steps_in_contact, pushed, peak, touched, rebound = 0, 0, 0.0, False, None
    for _ in range(20000):
        sim.DoStepDynamics()
        overlap = r - float(tr.Pos()[2])
        if overlap > 0:
            touched = True
            steps_in_contact += 1
            peak = max(peak, overlap)
            pushed += tr.ContactForce()[2] > 0
        elif touched:
            rebound = float(tr.Vel()[2])
            break
    assert touched and rebound is not None
    # The plane pushes up in every step that starts overlapped (the force of a step comes from
    # the positions it starts from: the first overlapped position has not been pushed yet).
    assert pushed == steps_in_contact - 1
    t_contact = steps_in_contact * dt
    assert abs(t_contact - tc) < 0.02 * tc, (t_contact, tc)
    assert abs(peak - delta_max) < 0.02 * delta_max, (peak, delta_max)
    assert abs(rebound - v) < 0.02 * v  # elastic: the speed comes back
    # The per-step calls from Python moved the same simulation as one call would have.
    assert abs(sim.GetSimTime() - (steps_in_contact + 10) * dt) < 3 * dt
