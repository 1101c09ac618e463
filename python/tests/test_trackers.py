"""Trackers from Python: setting state and reading it back, loads for the next call, meshes and
objects, and the batch calls on a resting layer."""
import gc

import numpy as np
import pytest

import deme
from conftest import material, quiet_solver, sphere_mass


def free_sphere(sim, pos=(0, 0, 0), g=(0, 0, 0)):
    mat = material(sim)
    sim.InstructBoxDomainDimension(2, 2, 2)
    tmpl = sim.LoadSphereType(sphere_mass(0.01, 1000), 0.01, mat)
    ball = sim.AddClumps(tmpl, [pos])
    sim.SetInitTimeStep(1e-4)
    sim.SetGravitationalAcceleration(list(g))
    sim.Initialize()
    return ball, sim.Track(ball)


def test_set_pos_vel_then_move(sim):
    _, tr = free_sphere(sim)
    tr.SetPos([0.1, -0.2, 0.3])
    tr.SetVel(np.array([1.0, 0.5, -0.25]))
    np.testing.assert_allclose(tr.Pos(), [0.1, -0.2, 0.3], atol=1e-6)
    np.testing.assert_array_equal(tr.Vel(), np.float32([1.0, 0.5, -0.25]))
    sim.DoDynamics(0.2)  # 2000 steps, no force: x = x0 + v t
    np.testing.assert_allclose(tr.Pos(), [0.3, -0.1, 0.25], atol=1e-5)


def test_added_acceleration_lasts_one_call(sim):
    # Semi-implicit Euler under a constant a for n steps of dt: v = a n dt and
    # x = a dt^2 n (n + 1) / 2 (exactly, as the integrator adds v after updating it).
    _, tr = free_sphere(sim)
    a, n, dt = np.array([2.0, 0.0, -1.0]), 1000, 1e-4
    tr.AddAcc(a)
    sim.DoDynamics(n * dt)
    # (to float32 round-off: velocities are float32 sums of n increments)
    np.testing.assert_allclose(tr.Vel(), a * n * dt, rtol=1e-4)
    np.testing.assert_allclose(tr.Pos(), a * dt * dt * n * (n + 1) / 2, rtol=1e-4, atol=1e-7)
    v_after = np.array(tr.Vel())
    sim.DoDynamics(n * dt)  # the load is gone: constant velocity
    np.testing.assert_allclose(tr.Vel(), v_after, rtol=1e-6)


def test_spin_and_orientation(sim):
    _, tr = free_sphere(sim)
    tr.SetAngVel([0, 0, np.pi])  # body frame; pi rad/s about z for 0.5 s: a quarter turn
    sim.DoDynamics(0.5)
    q = tr.OriQ()  # x, y, z, w: a turn by angle a about z is (0, 0, sin(a/2), cos(a/2))
    np.testing.assert_allclose(q, [0, 0, np.sin(np.pi / 4), np.cos(np.pi / 4)], atol=1e-4)
    np.testing.assert_allclose(tr.AngVelGlobal(), [0, 0, np.pi], rtol=1e-5)
    tr.SetOriQ([0, 0, 0, 2.0])  # normalised by the engine
    np.testing.assert_allclose(tr.OriQ(), [0, 0, 0, 1], atol=1e-7)


def test_resting_layer_contact_forces_balance_weight():
    # Spheres apart from each other, resting on a floor: each one's contact force is its weight
    # (force balance at rest, 1 %), pointing up, with no net torque.
    sim = quiet_solver()
    mat = material(sim, CoR=0.3, mu=0.5)
    sim.InstructBoxDomainDimension(1, 1, 1)
    sim.AddBCPlane([0, 0, -0.4], [0, 0, 1], mat)
    r, m = 0.01, sphere_mass(0.01, 2600)
    tmpl = sim.LoadSphereType(m, r, mat)
    grid = deme.GridSampler(0.03).SampleBox([0, 0, -0.4 + r * 1.01], [0.1, 0.1, 0])
    layer = sim.AddClumps(tmpl, grid)
    sim.SetInitTimeStep(2e-5)
    sim.SetGravitationalAcceleration([0, 0, -9.81])
    sim.Initialize()
    tr = sim.Track(layer)
    sim.DoDynamics(0.3)
    f = tr.ContactForces()
    assert f.shape == (len(grid), 3)
    np.testing.assert_allclose(f[:, 2], m * 9.81, rtol=0.01)
    assert np.abs(f[:, :2]).max() < 1e-3 * m * 9.81
    assert np.abs(tr.ContactTorques()).max() < 1e-3 * m * 9.81 * r
    np.testing.assert_allclose(tr.ContactAcc(3), [0, 0, 9.81], rtol=0.01, atol=1e-3)
    # Lift the whole layer from Python in one call; it falls back down.
    lifted = tr.Positions() + np.float32([0, 0, 0.05])
    tr.SetPositions(lifted)
    tr.SetVelocities(np.zeros_like(lifted))
    np.testing.assert_allclose(tr.Positions(), lifted, atol=1e-6)
    sim.DoDynamics(0.01)
    assert (tr.Positions()[:, 2] < lifted[:, 2]).all() and not tr.ContactForces().any()


def test_mesh_and_object_trackers():
    sim = quiet_solver()
    mat = material(sim)
    sim.InstructBoxDomainDimension(1, 1, 1)
    mesh = sim.AddWavefrontMeshObject(deme.GetDEMEDataFile("mesh/internal_mixer.obj"), mat)
    mesh.Scale(0.2)
    mesh.SetFamily(3)
    sim.SetFamilyPrescribedAngVel(3, "0", "0", "2*pi")
    wall = sim.AddExternalObject()
    wall.AddPlane([0, 0, 0], [0, 0, 1], mat)
    wall.SetInitPos([0, 0, -0.45])
    sim.AddClumps(sim.LoadSphereType(1.0, 0.01, mat), [[0.3, 0.3, 0.3]])
    sim.SetInitTimeStep(1e-4)
    sim.Initialize()
    tm, tw = sim.Track(mesh), sim.Track(wall)
    assert tm.GetNumOwners() == 1 and tm.GetOwnerID() == mesh.GetOwnerID()
    np.testing.assert_allclose(tw.Pos(), [0, 0, -0.45], atol=1e-6)
    sim.DoDynamics(0.125)  # an eighth of a turn
    np.testing.assert_allclose(tm.AngVelGlobal(), [0, 0, 2 * np.pi], rtol=1e-5)
    np.testing.assert_allclose(tm.OriQ(), [0, 0, np.sin(np.pi / 8), np.cos(np.pi / 8)], atol=1e-4)
    tm.SetPos([0.1, 0, 0])
    np.testing.assert_allclose(tm.Positions(), [[0.1, 0, 0]], atol=1e-6)


def test_tracker_keeps_its_solver_alive():
    sim = quiet_solver()
    _, tr = free_sphere(sim, pos=(0.1, 0, 0))
    del sim
    gc.collect()
    np.testing.assert_allclose(tr.Pos(), [0.1, 0, 0], atol=1e-6)  # no dangling solver


def test_offset_out_of_range_is_an_error(sim):
    _, tr = free_sphere(sim)
    with pytest.raises(deme.Error, match=r"^DEMTracker: offset 1 is out of range \(tracking 1 owners\)$"):
        tr.Pos(1)
