# The run statistics from Python: asynchronous contact sets and the dynamics side's wait share, and
# ClearThreadCollaborationStats starting them afresh (a settling phase left out of them).
import deme
from conftest import material, quiet_solver, sphere_mass


def pouring_block(sync):
    r = 0.0025
    sim = quiet_solver()
    mat = material(sim, E=1e7, CoR=0.3, mu=0.5)
    sim.InstructBoxDomainDimension(0.1, 0.1, 0.1)
    sim.InstructBoxDomainBoundingBC("top_open", mat)
    pts = deme.HCPSampler(2.05 * r).SampleBox([0, 0, -0.0385], [0.02, 0.02, 0.008])
    sim.AddClumps(sim.LoadSphereType(sphere_mass(r, 2600), r, mat), pts)
    sim.SetInitTimeStep(2e-5)
    sim.SetGravitationalAcceleration([0, 0, -9.81])
    sim.SetSynchronousContactDetection(sync)
    sim.Initialize()
    return sim


def test_cleared_counters_describe_the_run_after():
    sim = pouring_block(sync=False)
    sim.DoDynamics(0.03)
    assert sim.GetNumAsyncContactSetUpdates() > 0
    sim.ClearThreadCollaborationStats()
    assert sim.GetNumAsyncContactSetUpdates() == 0
    assert sim.GetDynamicsWaitShare() == 0.0
    sim.DoDynamics(0.02)
    assert sim.GetNumAsyncContactSetUpdates() > 0
    assert 0.0 <= sim.GetDynamicsWaitShare() <= 1.0


def test_synchronous_detection_never_waits_for_an_order():
    sim = pouring_block(sync=True)
    sim.DoDynamics(0.02)
    assert sim.GetNumAsyncContactSetUpdates() == 0
    assert sim.GetDynamicsWaitShare() == 0.0
