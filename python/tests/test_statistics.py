# The run statistics from Python: asynchronous contact sets and the dynamics side's wait share, and
# ClearThreadCollaborationStats starting them afresh (a settling phase left out of them).
from conftest import pouring_block as conftest_block


def pouring_block(sync):
    sim, _ = conftest_block(sync)
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
