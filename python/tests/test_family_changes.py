"""Family changes from Python: ChangeFamilyWhen freezes the grains that cross a plane (checked at
each contact detection, so at most one detection interval after they crossed), the tracker's
SetFamily / SetFamilies / GetFamilies, and bad input as deme.Error."""
import numpy as np
import pytest

import deme
from conftest import material, sphere_mass

N = 20
DT = 1e-4
CD_FREQ = 20


def row(sim):
    """N spheres 5 cm apart along y at x = -0.5, moving in +x at 0.1 i + 0.013 m/s, no gravity."""
    mat = material(sim)
    sim.InstructBoxDomainDimension(4, 4, 4)
    tmpl = sim.LoadSphereType(sphere_mass(0.01, 1000), 0.01, mat)
    pts = np.array([[-0.5, -0.5 + 0.05 * i, 0.0] for i in range(N)])
    batch = sim.AddClumps(tmpl, pts)
    speeds = np.float32([0.1 * i + 0.013 for i in range(N)])
    batch.SetVel([[float(v), 0.0, 0.0] for v in speeds])
    sim.SetFamilyFixed(1)
    sim.SetInitTimeStep(DT)
    sim.SetGravitationalAcceleration([0, 0, 0])
    sim.SetSynchronousContactDetection(True)
    sim.DisableAdaptiveUpdateFreq()
    sim.SetCDUpdateFreq(CD_FREQ)
    return batch, speeds


def test_change_family_when_freezes_grains_past_a_plane(sim):
    batch, speeds = row(sim)
    sim.ChangeFamilyWhen(0, 1, "X > 0")
    sim.Initialize()
    tr = sim.Track(batch)
    sim.DoDynamics(0.5)
    t = sim.GetSimTime()
    free_x = -0.5 + speeds * t
    fams = tr.GetFamilies()
    assert fams.dtype == np.uint32 and fams.shape == (N,)
    x = tr.Positions()[:, 0]
    crossed = free_x > 0
    assert crossed.sum() == 10  # grains 10..19 (v >= 1.013 m/s) pass x = 0 within 0.5 s
    np.testing.assert_array_equal(fams, np.where(crossed, 1, 0))
    assert np.all(x[crossed] > 0)
    assert np.all(x[crossed] <= speeds[crossed] * CD_FREQ * DT * (1 + 1e-3) + 1e-6)
    np.testing.assert_allclose(x[~crossed], free_x[~crossed], atol=1e-5)
    np.testing.assert_array_equal(tr.Velocities()[crossed, 0], 0)


def test_cleared_conditions_catch_no_more_grains(sim):
    batch, speeds = row(sim)
    sim.ChangeFamilyWhen(0, 1, "X > 0")
    sim.Initialize()
    tr = sim.Track(batch)
    sim.DoDynamics(0.4)  # past the plane by then: v > 1.25 m/s, grains 13..19
    caught = tr.GetFamilies().copy()
    assert caught.sum() > 0
    sim.ClearFamilyChangeConditions()
    sim.DoDynamics(0.1)  # grains 10..12 cross now
    np.testing.assert_array_equal(tr.GetFamilies(), caught)
    free_x = -0.5 + speeds * sim.GetSimTime()
    flying = caught == 0
    assert (free_x[flying] > 0).any()  # some crossed the plane after the conditions went
    np.testing.assert_allclose(tr.Positions()[flying, 0], free_x[flying], atol=1e-5)


def test_tracker_set_family_and_bad_input(sim):
    batch, speeds = row(sim)
    with pytest.raises(deme.Error, match="ChangeFamilyWhen"):
        sim.ChangeFamilyWhen(0, 1, "Q > 0")
    sim.Initialize()
    tr = sim.Track(batch)
    tr.SetFamily(1, 3)
    sim.DoDynamics(0.1)
    assert tr.GetFamily(3) == 1
    assert tr.Pos(3)[0] == pytest.approx(-0.5, abs=1e-7)  # frozen from the start
    with pytest.raises(deme.Error, match="SetFamilies"):
        tr.SetFamilies([0] * (N - 1) + [999])
    np.testing.assert_array_equal(tr.GetFamilies(), [1 if i == 3 else 0 for i in range(N)])
    tr.SetFamilies(np.zeros(N, dtype=np.uint32))
    assert tr.GetFamily(3) == 0
