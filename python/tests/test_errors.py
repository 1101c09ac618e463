"""Every error path of the module: deme::Error arrives as deme.Error (a RuntimeError) with the C++
message, naming the call (and file:line for files); arguments of the wrong type raise TypeError
naming the call; nothing takes the interpreter down, and the solver stays usable."""
import numpy as np
import pytest

import deme
from conftest import material, quiet_solver


def test_error_is_a_runtime_error_with_the_cpp_message(sim):
    assert issubclass(deme.Error, RuntimeError)
    with pytest.raises(deme.Error) as err:
        sim.SetVerbosity("LOUD")
    # The exact text deme::Error carries (src/api/DEMSolver.cpp).
    assert str(err.value) == 'SetVerbosity: unknown level "LOUD" (QUIET, ERROR, WARNING, INFO, STEP_METRIC)'
    sim.SetVerbosity("QUIET")  # and the solver goes on


def test_file_errors_name_file_and_line(sim, tmp_path):
    mat = material(sim)
    bad = tmp_path / "bad.csv"
    bad.write_text("x,y,z,r\n0,0,0,0.1\n0,0,zero,0.1\n")
    with pytest.raises(deme.Error, match=r"^LoadClumpType: .*bad\.csv:3: "):
        sim.LoadClumpType(1.0, [1, 1, 1], str(bad), mat)
    obj = tmp_path / "bad.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with pytest.raises(deme.Error, match=r"^AddWavefrontMeshObject: .*bad\.obj:4: "):
        sim.AddWavefrontMeshObject(str(obj), mat)
    with pytest.raises(deme.Error, match=r"^LoadClumpType: .*missing\.csv:0: cannot open file"):
        sim.LoadClumpType(1.0, [1, 1, 1], str(tmp_path / "missing.csv"), mat)


def test_missing_data_file_names_it():
    with pytest.raises(deme.Error, match=r'^GetDEMEDataFile: no data file "mesh/no_such\.obj" in '):
        deme.GetDEMEDataFile("mesh/no_such.obj")
    with pytest.raises(deme.Error, match=r"^GetDEMEDataFile: .* is an absolute path"):
        deme.GetDEMEDataFile("/etc/passwd")


def test_bad_values_are_deme_errors(sim):
    mat = material(sim)
    with pytest.raises(deme.Error, match=r"^DoDynamics: "):
        sim.DoDynamics(0.1)  # not initialized
    with pytest.raises(deme.Error, match=r"^InstructBoxDomainBoundingBC: "):
        sim.InstructBoxDomainBoundingBC("sideways", mat)
    with pytest.raises(deme.Error, match=r"^HCPSampler"):
        deme.HCPSampler(-1.0)
    with pytest.raises(deme.Error, match=r"^DEMMaterial::Get: the material has no property \"zeta\""):
        mat.Get("zeta")
    with pytest.raises(deme.Error, match=r"^Track: batch is null"):
        sim.Track(None)  # None is a null handle, which C++ refuses
    with pytest.raises(deme.Error, match=r"family 300 is out of range"):
        sim.SetFamilyFixed(300)
    tmpl = sim.LoadSphereType(1.0, 0.01, mat)
    sim.InstructBoxDomainDimension(1, 1, 1)
    with pytest.raises(deme.Error, match=r"^SetFamilyPrescribedAngVel: "):
        sim.SetFamilyPrescribedAngVel(1, "0", "0", "3 +* t")
    batch = sim.AddClumps(tmpl, [[0, 0, 0]])
    with pytest.raises(deme.Error, match=r"^DEMClumpBatch::SetVel"):
        batch.SetVel(np.zeros((2, 3)))  # two velocities for one clump


def test_a_diverging_run_raises_and_names_the_owner():
    sim = quiet_solver()
    mat = material(sim)
    sim.InstructBoxDomainDimension(1, 1, 1)
    ball = sim.AddClumps(sim.LoadSphereType(1.0, 0.01, mat), [[0, 0, 0]])
    ball.SetVel([30, 0, 0])
    sim.SetErrorOutVelocity(20.0)
    sim.SetInitTimeStep(1e-4)
    sim.Initialize()
    with pytest.raises(deme.Error, match=r"^DoDynamics: simulation diverged .* owner 0 "):
        sim.DoDynamics(0.01)


@pytest.mark.parametrize("call, args, name", [
    ("SetVerbosity", (3,), "SetVerbosity"),
    ("SetOutputContent", (42,), "SetOutputContent"),
    ("LoadMaterial", ({"E": "stiff"},), "LoadMaterial"),
    ("LoadMaterial", ([1, 2],), "LoadMaterial"),
    ("InstructBoxDomainDimension", ("1", 1, 1), "InstructBoxDomainDimension"),
    ("SetGravitationalAcceleration", ([0, -9.81],), "SetGravitationalAcceleration"),
    ("SetGravitationalAcceleration", ("xyz",), "SetGravitationalAcceleration"),
    ("SetGravitationalAcceleration", (np.zeros((3, 3)),), "SetGravitationalAcceleration"),
    ("SetGravitationalAcceleration", ([0, None, 1],), "SetGravitationalAcceleration"),
    ("SetInitTimeStep", ("small",), "SetInitTimeStep"),
    ("Track", ("batch",), "Track"),
    ("DoDynamics", ("1 s",), "DoDynamics"),
])
def test_wrong_argument_types_raise_type_error_naming_the_call(sim, call, args, name):
    with pytest.raises(TypeError, match=r"^%s\(\): incompatible function arguments" % name):
        getattr(sim, call)(*args)


def test_wrong_array_shapes_raise_type_error(sim):
    mat = material(sim)
    tmpl = sim.LoadSphereType(1.0, 0.01, mat)
    sim.InstructBoxDomainDimension(1, 1, 1)
    for bad in (np.zeros((4, 2)), np.zeros(3), [[0, 0], [1, 1]], "positions", [[0, 0, "z"]], [[0, 0, 0], [1, 1]]):
        with pytest.raises(TypeError, match=r"^AddClumps\(\): incompatible function arguments"):
            sim.AddClumps(tmpl, bad)
    batch = sim.AddClumps(tmpl, np.zeros((2, 3)))
    with pytest.raises(TypeError, match=r"^SetOriQ\(\)"):
        batch.SetOriQ([0, 0, 1])  # a quaternion has 4 numbers
    with pytest.raises(TypeError, match=r"^SetOriQ\(\)"):
        batch.SetOriQ(np.zeros((2, 3)))
    with pytest.raises(TypeError, match=r"^AddCylinder\(\)"):
        sim.AddExternalObject().AddCylinder([0, 0], [0, 0, 1], 0.5, mat)
    with pytest.raises(TypeError, match=r"^LoadClumpType\(\)"):
        sim.LoadClumpType(1.0, [1, 1, 1], [0.01], [[0, 0]], mat)
    with pytest.raises(TypeError, match=r"^SetFamily\(\)"):
        batch.SetFamily([-1, 2])


def test_nan_and_inf_are_refused_not_clamped(sim):
    mat = material(sim)
    tmpl = sim.LoadSphereType(1.0, 0.01, mat)
    sim.InstructBoxDomainDimension(1, 1, 1)
    batch = sim.AddClumps(tmpl, [[0, 0, 0]])
    with pytest.raises(deme.Error, match=r"^DEMClumpBatch::SetVel: .*finite"):
        batch.SetVel([np.nan, 0, 0])
    with pytest.raises(deme.Error, match=r"^SetGravitationalAcceleration: .*finite"):
        sim.SetGravitationalAcceleration([0, 0, np.inf])


def test_exceptions_from_python_callbacks_propagate():
    sim = quiet_solver()
    mat = material(sim)
    sim.InstructBoxDomainDimension(1, 1, 1)
    sim.AddClumps(sim.LoadSphereType(1.0, 0.01, mat), [[0, 0, 0]])
    sim.SetInitTimeStep(1e-5)
    sim.Initialize()

    def check():
        raise ValueError("from the check")

    sim.SetInterruptCheck(check)
    with pytest.raises(ValueError, match="from the check"):
        sim.DoDynamics(10.0)  # long enough to be polled
    assert sim.WasInterrupted()
    sim.SetInterruptCheck(None)
    t = sim.GetSimTime()
    sim.DoDynamics(0.001)
    assert abs(sim.GetSimTime() - (t + 0.001)) < 1e-9 and not sim.WasInterrupted()
