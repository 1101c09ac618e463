"""A custom force model written in Python's host: a C++ snippet compiled at Initialize, with its
material properties and wildcards set and read from Python as numpy arrays."""
import numpy as np
import pytest

import deme
from conftest import material, quiet_solver, sphere_mass

# A linear spring-dashpot normal force, kn and cn per material (the sphere's: A is always the
# sphere), and two wildcards: `touched`, an owner wildcard the model sets, and `gain`, a geometry
# wildcard scaling the spring of the sphere it belongs to.
LINEAR_SPRING = """
    if (overlapDepth > 0.0) {
        const float vn = dot((ALinVel + rotVelCPA) - (BLinVel + rotVelCPB), B2A);
        const float k = kn[bodyAMatType] * gain[AGeo];
        force += (k * (float)overlapDepth - cn[bodyAMatType] * vn) * B2A;
        touched[AOwner] = 1.f;
    }
"""


def spheres_on_a_floor(n, r, m, kn, cn, called_for_apart_pairs=True):
    sim = quiet_solver()
    model = sim.DefineContactForceModel(LINEAR_SPRING)
    assert model.GetCalledForApartPairs()
    model.SetCalledForApartPairs(called_for_apart_pairs)
    model.SetMustHaveMatProp(["kn", "cn"])
    model.SetPerOwnerWildcards(["touched"])
    model.SetPerGeometryWildcards(["gain"])
    assert model.GetKind() == deme.DEMForceModel.Kind.CUSTOM
    assert model.GetMustHaveMatProp() == ["kn", "cn"] and model.GetPerOwnerWildcards() == ["touched"]
    mat = sim.LoadMaterial({"kn": kn, "cn": cn})
    sim.InstructBoxDomainDimension(1, 1, 1)
    sim.AddBCPlane([0, 0, -0.4], [0, 0, 1], mat)
    tmpl = sim.LoadSphereType(m, r, mat)
    # In a row 5 r apart: each touches the floor only.
    xyz = np.array([[-0.3 + 5 * r * i, 0, -0.4 + r] for i in range(n)])
    batch = sim.AddClumps(tmpl, xyz)
    sim.SetInitTimeStep(1e-5)
    sim.SetGravitationalAcceleration([0, 0, -9.81])
    return sim, batch


# The snippet acts only where the surfaces overlap, so whether it is called for apart pairs
# (SetCalledForApartPairs) changes nothing but the work done.
@pytest.mark.parametrize("called_for_apart_pairs", [True, False])
def test_custom_model_static_overlap_and_wildcards(called_for_apart_pairs):
    # A sphere resting on a linear spring kn * gain sinks by delta = m g / (kn * gain) at rest
    # (force balance; the dashpot cn brings it to rest: damping ratio about 0.4, so after 0.4 s the
    # oscillation has decayed by e^-50). Tolerance 1 % of delta.
    n, r, density, kn, cn = 4, 0.01, 1000.0, 411.0, 1.0
    m = sphere_mass(r, density)
    sim, batch = spheres_on_a_floor(n, r, m, kn, cn, called_for_apart_pairs)
    sim.Initialize()
    tr = sim.Track(batch)
    gains = np.array([1.0, 2.0, 0.5, 1.0], dtype=np.float32)
    sim.SetSphereWildcardValue("gain", 0, gains)
    np.testing.assert_array_equal(sim.GetSphereWildcardValue("gain", 0, n), gains)
    assert sim.GetOwnerWildcardValue("touched", 0, n).tolist() == [0.0] * n
    sim.DoDynamics(0.4)
    sink = (r - 0.4) - tr.Positions()[:, 2].astype(np.float64)  # sphere centre below r above the floor
    expected = m * 9.81 / (kn * gains.astype(np.float64))
    np.testing.assert_allclose(sink, expected, rtol=0.01)
    # The contact force on each sphere balances its weight; no torque from a central force.
    np.testing.assert_allclose(tr.ContactForces()[:, 2], m * 9.81, rtol=0.01)
    assert np.abs(tr.ContactTorques()).max() < 1e-9
    touched = sim.GetOwnerWildcardValue("touched", 0, n)
    assert touched.dtype == np.float32 and touched.tolist() == [1.0] * n
    # Set from Python, read back: whole ranges, one owner, through the tracker.
    sim.SetOwnerWildcardValue("touched", 0, np.zeros(n))
    assert tr.GetOwnerWildcardValue("touched", 2) == 0.0
    tr.SetOwnerWildcardValue("touched", 5.0, 1)
    assert sim.GetOwnerWildcardValue("touched", 1) == 5.0
    sim.SetFamilyOwnerWildcardValue(0, "touched", 2.0)
    assert sim.GetOwnerWildcardValue("touched", 0, n).tolist() == [2.0] * n
    with pytest.raises(deme.Error, match="no_such"):
        sim.GetOwnerWildcardValue("no_such", 0)


def test_custom_model_needs_its_material_properties():
    sim = quiet_solver()
    model = sim.DefineContactForceModel(LINEAR_SPRING)
    model.SetMustHaveMatProp(["kn", "cn"])
    model.SetPerOwnerWildcards(["touched"])
    model.SetPerGeometryWildcards(["gain"])
    mat = sim.LoadMaterial({"kn": 1.0})  # no cn
    sim.InstructBoxDomainDimension(1, 1, 1)
    sim.AddClumps(sim.LoadSphereType(1.0, 0.01, mat), [[0, 0, 0]])
    sim.SetInitTimeStep(1e-5)
    with pytest.raises(deme.Error, match=r"cn"):
        sim.Initialize()


def test_snippet_compile_error_names_its_line():
    sim = quiet_solver()
    sim.DefineContactForceModel("force += undefined_thing;\n")
    mat = material(sim)
    sim.InstructBoxDomainDimension(1, 1, 1)
    sim.AddClumps(sim.LoadSphereType(1.0, 0.01, mat), [[0, 0, 0]])
    sim.SetInitTimeStep(1e-5)
    with pytest.raises(deme.Error) as err:
        sim.Initialize()
    assert "undefined_thing" in str(err.value)


def test_built_in_model_sees_touching_pairs_only():
    model = quiet_solver().UseFrictionalHertzianModel()
    assert not model.GetCalledForApartPairs()
    with pytest.raises(deme.Error, match="SetCalledForApartPairs"):
        model.SetCalledForApartPairs(True)
