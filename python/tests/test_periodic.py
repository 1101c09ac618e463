# Periodic boundaries and the stress of the grains from Python: a grain that leaves through a
# periodic face comes back through the other with its velocity; a pressed pair's stress is F l / V;
# the stress field's cells, written to CSV, add up to the whole box. Bad input is deme.Error.
import csv

import numpy as np
import pytest

import deme
from conftest import material, quiet_solver, sphere_mass


def test_a_grain_crosses_a_periodic_face_with_its_velocity():
    sim = quiet_solver()
    mat = material(sim, E=1e7, CoR=0.5, mu=0.5)
    sim.InstructBoxDomainDimension((0.0, 0.1), (0.0, 0.1), (0.0, 0.1))
    sim.InstructBoxDomainPeriodicity("x")
    grain = sim.AddClumps(sim.LoadSphereType(sphere_mass(0.005, 2500), 0.005, mat), [[0.09, 0.05, 0.05]])
    sim.SetInitTimeStep(1e-4)
    sim.SetGravitationalAcceleration([0, 0, 0])
    sim.Initialize()
    tr = sim.Track(grain)
    tr.SetVel([1.0, 0, 0])
    sim.DoDynamics(0.02)  # 2 cm: through the face at x = 0.1
    assert tr.Pos()[0] == pytest.approx(0.01, abs=1e-6)
    assert np.allclose(tr.Vel(), [1.0, 0, 0], atol=1e-6)


def test_a_grain_through_a_sheared_cells_top_enters_displaced_and_slower():
    # Lees-Edwards (SetPeriodicShear): through the top at t_c = 0.02 s, the grain enters through the
    # bottom displaced by the offset rate * Lz * t_c and slower by rate * Lz along x.
    sim = quiet_solver()
    mat = material(sim, E=1e7, CoR=0.5, mu=0.5)
    L, rate, dt = 0.1, 20.0, 1e-4
    sim.InstructBoxDomainDimension((0.0, L), (0.0, L), (0.0, L))
    sim.InstructBoxDomainPeriodicity("xyz")
    sim.SetPeriodicShear(rate)
    grain = sim.AddClumps(sim.LoadSphereType(sphere_mass(0.005, 2500), 0.005, mat), [[0.05, 0.05, L - 0.0195]])
    sim.SetInitTimeStep(dt)
    sim.SetGravitationalAcceleration([0, 0, 0])
    sim.Initialize()
    tr = sim.Track(grain)
    tr.SetVel([0.0, 0, 1.0])  # 1 m/s up: through the top half-way through step 196, ending at 0.0196 s
    sim.DoDynamics(0.03)
    U, tc = rate * L, 0.0196
    offset = U * tc - L * round(U * tc / L)
    x = 0.05 - offset - U * (0.03 - tc)
    assert (tr.Pos()[0] - x) % L == pytest.approx(0.0, abs=1e-6) or (tr.Pos()[0] - x) % L == pytest.approx(L, abs=1e-6)
    assert tr.Vel()[0] == pytest.approx(-U, abs=1e-5)


def test_shear_needs_periodic_x_and_z():
    sim = quiet_solver()
    mat = material(sim, E=1e7, CoR=0.5, mu=0.5)
    sim.InstructBoxDomainDimension(0.1, 0.1, 0.1)
    sim.InstructBoxDomainPeriodicity("x")
    sim.SetPeriodicShear(1.0)
    sim.AddClumps(sim.LoadSphereType(sphere_mass(0.005, 2500), 0.005, mat), [[0, 0, 0]])
    sim.SetInitTimeStep(1e-4)
    with pytest.raises(deme.Error, match="periodic along x and z"):
        sim.Initialize()


def test_pressed_pair_stress_and_field():
    sim = quiet_solver()
    mat = material(sim, E=1e7, CoR=0.5, mu=0.4)
    sim.InstructBoxDomainDimension(0.2, 0.2, 0.2)
    r, l = 0.008, 0.0156
    pair = sim.AddClumps(sim.LoadSphereType(sphere_mass(r, 2500), r, mat), [[-l / 2, 0, 0], [l / 2, 0, 0]])
    sim.SetInitTimeStep(1e-6)
    sim.SetGravitationalAcceleration([0, 0, 0])
    sim.Initialize()
    stress = sim.CreateInspector("stress", [-0.05, -0.05, -0.05], [0.05, 0.05, 0.05])
    sim.DoStepDynamics()
    tr = sim.Track(pair)
    f = -tr.ContactForce(0)[0]
    s = stress.GetStress()
    assert s["total"].shape == (3, 3)
    assert s["grains"] == 2
    dist = tr.Pos(1)[0] - tr.Pos(0)[0]
    assert s["contact"][0, 0] == pytest.approx(f * dist / s["volume"], rel=1e-5)
    assert stress.GetValue() == pytest.approx(s["pressure"])


def test_stress_field_to_csv(tmp_path):
    sim = quiet_solver()
    mat = material(sim, E=1e7, CoR=0.5, mu=0.4)
    sim.InstructBoxDomainDimension(0.2, 0.2, 0.2)
    r = 0.008
    sim.AddClumps(sim.LoadSphereType(sphere_mass(r, 2500), r, mat), [[-0.0078, 0, 0], [0.0078, 0, 0]])
    sim.SetInitTimeStep(1e-6)
    sim.SetGravitationalAcceleration([0, 0, 0])
    sim.Initialize()
    sim.DoStepDynamics()
    path = str(tmp_path / "stress.csv")
    sim.WriteStressField(path, [-0.05, -0.05, -0.05], [0.05, 0.05, 0.05], 2, 1, 1)
    sim.FlushOutput()
    with open(path) as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 2
    assert [int(float(r["grains"])) for r in rows] == [1, 1]
    whole = sim.CreateInspector("stress", [-0.05, -0.05, -0.05], [0.05, 0.05, 0.05]).GetStress()
    sxx = sum(float(r["cxx"]) for r in rows) / 2
    assert sxx == pytest.approx(whole["contact"][0, 0], rel=1e-9)


def test_bad_input_is_deme_error():
    sim = quiet_solver()
    with pytest.raises(deme.Error, match="InstructBoxDomainPeriodicity"):
        sim.InstructBoxDomainPeriodicity("q")
    with pytest.raises(deme.Error, match="takes a region"):
        sim.CreateInspector("stress")
