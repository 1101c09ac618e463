"""Checkpoint and restart from Python (docs/checkpoint.md): N steps, a checkpoint, a new solver of
the same script that reads it and N more steps equal 2N straight steps bit for bit on the CPU; bad
files raise deme.Error saying what is wrong, and change nothing."""
import os

import numpy as np
import pytest

import deme
from conftest import material, quiet_solver

STEPS = 600


def pile(backend=None, mu=0.5):
    """A small pile of spheres dropped into a box, up to Initialize(), and a tracker of it. The
    backend: as given, or DEME_BACKEND's (tests/gpu/run.sh runs this file with cuda)."""
    sim = quiet_solver()
    if backend:
        sim.SetBackend(backend)
    sim.SetProgressReport(False)
    mat = material(sim, E=1e7, CoR=0.4, mu=mu)
    sim.InstructBoxDomainDimension(0.1, 0.1, 0.2)
    sim.InstructBoxDomainBoundingBC("top_open", mat)
    pts = deme.HCPSampler(0.0058).SampleBox([0, 0, -0.085], [0.02, 0.02, 0.01])
    grains = sim.AddClumps(sim.LoadSphereType(1e-3, 0.003, mat), pts)
    sim.SetInitTimeStep(2e-5)
    sim.SetSynchronousContactDetection(True)
    sim.SetGravitationalAcceleration([0, 0, -9.81])
    sim.Initialize()
    return sim, sim.Track(grains)


def state(tr):
    return np.concatenate([tr.Positions().ravel(), tr.Velocities().ravel(), tr.AngularVelocities().ravel(),
                           tr.OriQs().ravel()])


def steps(sim, n):
    for _ in range(n):
        sim.DoStepDynamics()


def test_restart_is_bit_for_bit_on_the_cpu(tmp_path):
    path = str(tmp_path / "run.ckpt")
    straight, tr = pile("cpu")  # the CPU's steps are under test, bit for bit
    steps(straight, STEPS)
    straight.WriteCheckpoint(path)
    steps(straight, STEPS)
    restarted, tr2 = pile("cpu")
    restarted.ReadCheckpoint(path)
    assert restarted.GetSimTime() == pytest.approx(STEPS * 2e-5, rel=1e-12)
    steps(restarted, STEPS)
    assert restarted.GetSimTime() == straight.GetSimTime()
    assert restarted.GetNumContacts() == straight.GetNumContacts() > 0
    np.testing.assert_array_equal(state(tr2), state(tr))


def test_bad_checkpoints_raise_and_change_nothing(tmp_path):
    good = str(tmp_path / "good.ckpt")
    writer, _ = pile()
    steps(writer, 50)
    writer.WriteCheckpoint(good)
    data = open(good, "rb").read()

    sim, tr = pile()
    before = state(tr)
    bad = str(tmp_path / "bad.ckpt")
    cases = {
        "truncated": data[: len(data) // 2],
        "checksum": data[:100] + bytes([data[100] ^ 1]) + data[101:],
        "not a checkpoint": b"hello",
    }
    for what, content in cases.items():
        with open(bad, "wb") as f:
            f.write(content)
        with pytest.raises(deme.Error, match=what):
            sim.ReadCheckpoint(bad)
        np.testing.assert_array_equal(state(tr), before)

    other, _ = pile(mu=0.3)
    other.WriteCheckpoint(bad)
    with pytest.raises(deme.Error, match="another scene"):
        sim.ReadCheckpoint(bad)
    np.testing.assert_array_equal(state(tr), before)
    assert sim.GetSimTime() == 0.0

    sim.ReadCheckpoint(good)  # the good one still reads
    assert sim.GetSimTime() == pytest.approx(50 * 2e-5, rel=1e-12)
    assert not [n for n in os.listdir(tmp_path) if n.startswith(".")]  # no temporary files left
