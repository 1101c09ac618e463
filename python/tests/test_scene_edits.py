"""Scenes that change while they run, from Python: clumps added after Initialize (AddClumps, then
UpdateClumps), removed by family, and removed when they leave the domain (SetDomainExitPolicy)."""
import numpy as np
import pytest

import deme
from conftest import material, sphere_mass


def falling_scene(sim, policy=None):
    """Two spheres in free fall in a box without walls; the domain's floor is 0.5 m below them."""
    mat = material(sim)
    sim.InstructBoxDomainDimension(1, 1, 1)
    tmpl = sim.LoadSphereType(sphere_mass(0.01, 1000), 0.01, mat)
    first = sim.AddClumps(tmpl, [[0, 0, 0], [0.2, 0, 0]])
    first.SetFamily(1)
    sim.SetInitTimeStep(1e-4)
    sim.SetGravitationalAcceleration([0, 0, -9.81])
    if policy:
        sim.SetDomainExitPolicy(policy)
    sim.Initialize()
    return mat, tmpl, first


def test_added_batch_gets_ids_after_the_existing_ones(sim):
    _, tmpl, first = falling_scene(sim)
    tr_first = sim.Track(first)
    sim.DoDynamics(0.01)
    batch = sim.AddClumps(tmpl, [[-0.2, 0, 0.3]])
    batch.SetVel([1.0, 0, 0])
    with pytest.raises(deme.Error, match="UpdateClumps"):
        sim.DoDynamics(0.01)
    sim.UpdateClumps()
    tr = sim.Track(batch)
    assert sim.GetNumClumps() == 3
    assert tr.GetOwnerID(0) == 2
    np.testing.assert_allclose(tr.Pos(), [-0.2, 0, 0.3], atol=1e-6)
    sim.DoDynamics(0.1)
    # Free fall from rest for the new sphere: x = v t, z = z0 - g t^2 / 2 (to the integrator's order).
    np.testing.assert_allclose(tr.Pos(), [-0.2 + 0.1, 0, 0.3 - 0.5 * 9.81 * 0.1 ** 2], atol=1e-3)
    assert tr_first.GetOwnerID(1) == 1


def test_remove_family_keeps_the_other_ids(sim):
    _, tmpl, first = falling_scene(sim)
    batch = sim.AddClumps(tmpl, [[-0.2, 0, 0.3]])
    batch.SetFamily(2)
    sim.UpdateClumps()
    tr = sim.Track(batch)
    assert sim.RemoveClumpsInFamily(1) == 2
    assert sim.GetNumClumps() == 1
    assert sim.GetNumRemovedClumps() == 2
    assert sim.GetRemovedMass() == pytest.approx(2 * sphere_mass(0.01, 1000), rel=1e-6)
    assert tr.GetOwnerID(0) == 2
    with pytest.raises(deme.Error, match="was removed"):
        sim.Track(first).Pos(0)
    sim.DoDynamics(0.01)


def test_exit_policy_remove_takes_out_leaving_grains(sim):
    falling_scene(sim, policy="remove")
    mass = sim.CreateInspector("clump_mass")
    initial = mass.GetValue()
    sim.DoDynamics(0.4)  # both fall 0.5 m in 0.32 s
    assert sim.GetNumClumps() == 0
    assert sim.GetNumRemovedClumps() == 2
    assert sim.GetRemovedMass() + mass.GetValue() == initial


def test_bad_input():
    sim = deme.DEMSolver()
    sim.SetVerbosity("QUIET")
    with pytest.raises(deme.Error, match="SetDomainExitPolicy"):
        sim.SetDomainExitPolicy("vanish")
    with pytest.raises(deme.Error, match="UpdateClumps"):
        sim.UpdateClumps()
    _, tmpl, _ = falling_scene(sim)
    with pytest.raises(deme.Error, match="AddClumps.*outside the simulation domain"):
        sim.AddClumps(tmpl, [[0, 0, 0.9]])
    with pytest.raises(deme.Error, match="RemoveClumpsInFamily"):
        sim.RemoveClumpsInFamily(300)
