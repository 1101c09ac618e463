"""Long runs: DoDynamics releases the GIL while it steps, and Ctrl-C (SIGINT) stops it at a step
boundary within a fraction of a second (the check runs every 50 ms at most), leaving a solver
that runs on."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import deme
from conftest import material, quiet_solver, sphere_mass

DT = 1e-5


def settling_bed():
    sim = quiet_solver()
    mat = material(sim)
    sim.InstructBoxDomainDimension(0.4, 0.4, 0.4)
    sim.InstructBoxDomainBoundingBC("top_open", mat)
    tmpl = sim.LoadSphereType(sphere_mass(0.005, 2600), 0.005, mat)
    batch = sim.AddClumps(tmpl, deme.GridSampler(0.0125).SampleBox([0, 0, 0], [0.05, 0.05, 0.05]))
    sim.SetInitTimeStep(DT)
    sim.SetGravitationalAcceleration([0, 0, -9.81])
    sim.Initialize()
    return sim, sim.Track(batch)


def assert_at_a_step_boundary(sim):
    steps = sim.GetSimTime() / DT
    assert abs(steps - round(steps)) < 1e-6 * steps


def test_ctrl_c_stops_a_long_run_which_then_goes_on():
    sim, tr = settling_bed()
    sent = {}

    def interrupt():
        sent["t"] = time.monotonic()
        os.kill(os.getpid(), signal.SIGINT)

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.5, interrupt)
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            sim.DoDynamics(1000.0)  # 1e8 steps: hours, unless stopped
        caught = time.monotonic()
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    # Within a fraction of a second: the check is polled every 50 ms (and every 8 steps).
    assert caught - sent["t"] < 0.5, caught - sent["t"]
    assert sim.WasInterrupted()
    t_stop = sim.GetSimTime()
    assert 0 < t_stop < 1000.0
    assert_at_a_step_boundary(sim)
    pos = tr.Positions()
    assert np.isfinite(pos).all() and np.isfinite(tr.Velocities()).all()
    # The run goes on from there, for exactly the time asked.
    sim.DoDynamics(0.01)
    assert not sim.WasInterrupted()
    assert abs(sim.GetSimTime() - (t_stop + 0.01)) < 0.5 * DT
    assert not np.array_equal(tr.Positions(), pos)


def test_do_dynamics_releases_the_gil():
    # A thread that wakes every millisecond needs the GIL at each wake-up. While DoDynamics runs
    # with the GIL released it wakes hundreds of times in 0.5 s; were the GIL held, it could wake
    # only when the interrupt check takes the GIL (every 50 ms): about 10 times.
    sim, _ = settling_bed()
    wakeups, stop = [0], threading.Event()

    def ticker():
        while not stop.is_set():
            time.sleep(0.001)
            wakeups[0] += 1

    thread = threading.Thread(target=ticker)
    t_end = time.monotonic() + 0.5
    sim.SetInterruptCheck(lambda: time.monotonic() > t_end)
    thread.start()
    try:
        sim.DoDynamics(1000.0)
    finally:
        stop.set()
        thread.join()
    assert sim.WasInterrupted()
    assert wakeups[0] > 100, wakeups[0]


def test_user_check_stops_every_stepping_call():
    sim, _ = settling_bed()
    sim.SetInterruptCheck(lambda: True)
    for run in (lambda: sim.DoDynamics(1000.0), lambda: sim.DoDynamicsThenSync(1000.0)):
        t0 = sim.GetSimTime()
        run()
        assert sim.WasInterrupted() and t0 < sim.GetSimTime() < t0 + 1.0
        assert_at_a_step_boundary(sim)
    sim.SetInterruptCheck(None)
    t0 = sim.GetSimTime()
    sim.DoStepDynamics()
    assert abs(sim.GetSimTime() - (t0 + DT)) < 1e-12 and not sim.WasInterrupted()
