"""numpy in and out: shapes, dtypes, C order, and rows in user id order (owners are stored in a
space-filling-curve order inside; users see them in the order they added them)."""
import numpy as np
import pytest

import deme
from conftest import material, sphere_mass


def random_scene(sim, rng, n=500, second=50):
    """n + second spheres at random, well-separated places (so that their storage order differs
    from the order they were added), in zero gravity."""
    mat = material(sim)
    sim.InstructBoxDomainDimension(2, 2, 2)
    tmpl = sim.LoadSphereType(sphere_mass(0.01, 1000), 0.01, mat)
    cells = rng.permutation(20 ** 3)[: n + second]  # one sphere per 0.05 m cell: no contacts
    ijk = np.stack([cells % 20, (cells // 20) % 20, cells // 400], axis=1)
    pts = ((ijk + 0.5) * 0.05 - 0.5).astype(np.float32)
    a = sim.AddClumps(tmpl, pts[:n])
    b = sim.AddClumps(tmpl, pts[n:].tolist())  # nested lists work too
    sim.SetInitTimeStep(1e-5)
    sim.SetGravitationalAcceleration([0, 0, 0])
    return a, b, pts


def test_samplers_return_n_by_3_float32():
    for sampler in (deme.HCPSampler(0.1), deme.GridSampler(0.1)):
        for pts in (sampler.SampleBox([0, 0, 0], [0.5, 0.4, 0.3]), sampler.SampleCylinderZ((0, 0, 0), 0.5, 0.3),
                    sampler.SampleCylinderX(np.zeros(3), 0.5, 0.3), sampler.SampleSphere([0, 0, 0], 0.5)):
            assert isinstance(pts, np.ndarray) and pts.dtype == np.float32
            assert pts.ndim == 2 and pts.shape[1] == 3 and pts.shape[0] > 10 and pts.flags.c_contiguous
            # Nearest neighbours at exactly the spacing (HCP and the grid alike).
            d = np.linalg.norm(pts[:, None, :] - pts[None, :, :], axis=2)
            np.fill_diagonal(d, np.inf)
            np.testing.assert_allclose(d.min(axis=1), 0.1, rtol=1e-4)
    box = deme.GridSampler(0.1).SampleBox([0, 0, 0], [0.2, 0.2, 0.2])
    assert box.shape == (125, 3)


def test_tracker_batches_match_user_order(sim, rng):
    a, b, pts = random_scene(sim, rng)
    n = a.GetNumClumps()
    vel = rng.uniform(-1, 1, (n, 3)).astype(np.float32)
    w = rng.uniform(-5, 5, (n, 3)).astype(np.float32)
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    a.SetVel(vel)
    a.SetAngVel(w)
    a.SetOriQ(q)
    b.SetVel([0.5, 0, 0])
    sim.Initialize()
    ta, tb = sim.Track(a), sim.Track(b)
    assert [ta.GetOwnerID(i) for i in (0, 1, n - 1)] == [0, 1, n - 1]
    assert tb.GetOwnerID(0) == n and tb.GetNumOwners() == len(pts) - n

    for arr, cols in ((ta.Positions(), 3), (ta.Velocities(), 3), (ta.AngularVelocities(), 3), (ta.OriQs(), 4),
                      (ta.ContactForces(), 3), (ta.ContactTorques(), 3)):
        assert arr.dtype == np.float32 and arr.shape == (n, cols) and arr.flags.c_contiguous
    # Positions to the compact format's resolution (well below a micrometre in a 2 m domain).
    np.testing.assert_allclose(ta.Positions(), pts[:n], atol=1e-6)
    np.testing.assert_allclose(tb.Positions(), pts[n:], atol=1e-6)
    np.testing.assert_array_equal(ta.Velocities(), vel)
    np.testing.assert_array_equal(tb.Velocities(), np.tile([0.5, 0, 0], (len(pts) - n, 1)).astype(np.float32))
    np.testing.assert_allclose(ta.OriQs(), q, atol=1e-6)
    # Global angular velocity: the local one rotated by q (x, y, z, w with w the scalar part):
    # v' = v + 2 w (u x v) + 2 u x (u x v) with u the vector part.
    u, s = q[:, :3], q[:, 3:4]
    uv = np.cross(u, w)
    np.testing.assert_allclose(ta.AngularVelocities(), w + 2 * s * uv + 2 * np.cross(u, uv), atol=1e-5)
    # The batch forms agree with the per-owner calls row for row.
    for i in (0, 7, n - 1):
        np.testing.assert_array_equal(ta.Positions()[i], ta.Pos(i))
        np.testing.assert_array_equal(ta.AngularVelocities()[i], ta.AngVelGlobal(i))
        np.testing.assert_array_equal(ta.OriQs()[i], ta.OriQ(i))
        np.testing.assert_array_equal(ta.Velocities()[i], ta.Vel(i))
    # No contacts: zero forces and torques.
    assert not ta.ContactForces().any() and not ta.ContactTorques().any()


def test_batch_setters_round_trip(sim, rng):
    a, b, pts = random_scene(sim, rng)
    sim.Initialize()
    ta = sim.Track(a)
    n = ta.GetNumOwners()
    new_pos = pts[:n][::-1].copy()  # the same places, in reverse: still no two in contact
    ta.SetPositions(new_pos)
    np.testing.assert_allclose(ta.Positions(), new_pos, atol=1e-6)
    v = rng.uniform(-1, 1, (n, 3))  # float64 is converted
    ta.SetVelocities(v)
    np.testing.assert_allclose(ta.Velocities(), v.astype(np.float32))
    # They move on from there: x = x0 + v t exactly in zero gravity without contacts.
    sim.DoDynamics(0.01)
    np.testing.assert_allclose(ta.Positions(), new_pos + 0.01 * v, atol=1e-5)
    # Wrong row count: deme.Error from C++, naming the call; nothing changed.
    before = ta.Positions()
    with pytest.raises(deme.Error, match=r"DEMTracker::SetPositions: got 3 positions for 500 owners"):
        ta.SetPositions(np.zeros((3, 3)))
    # A row outside the domain: nothing changed either (all rows are checked first).
    bad = before.copy()
    bad[-1] = [5, 0, 0]
    with pytest.raises(deme.Error, match=r"DEMTracker::SetPositions: position row 499 .* outside the simulation domain"):
        ta.SetPositions(bad)
    np.testing.assert_array_equal(ta.Positions(), before)
    bad[-1] = [np.nan, 0, 0]
    with pytest.raises(deme.Error, match=r"must be finite"):
        ta.SetVelocities(bad)


def test_batch_getters_before_initialize_raise(sim, rng):
    a, _, _ = random_scene(sim, rng, n=10, second=1)
    tr = sim.Track(a)
    with pytest.raises(deme.Error, match=r"^DEMTracker::Positions: the solver is not initialized yet"):
        tr.Positions()


def test_batch_inputs_before_initialize(sim):
    mat = material(sim)
    sim.InstructBoxDomainDimension(1, 1, 1)
    tmpl = sim.LoadSphereType(1.0, 0.01, mat)
    pts = np.array([[0, 0, 0], [0.1, 0, 0], [0.2, 0, 0]], dtype=np.float64)
    batch = sim.AddClumps(tmpl, pts)
    np.testing.assert_array_equal(batch.GetPositions(), pts.astype(np.float32))
    assert batch.GetPositions().dtype == np.float32
    batch.SetFamily([1, 2, 3])
    families = batch.GetFamilies()
    assert families.dtype == np.uint8 and families.tolist() == [1, 2, 3]
    batch.SetOriQ(np.array([[0, 0, 0, 1.0]] * 3))
    np.testing.assert_array_equal(batch.GetOriQs(), [[0, 0, 0, 1]] * 3)
    batch.SetAngVel((1, 2, 3))
    np.testing.assert_array_equal(batch.GetAngVelocities(), [[1, 2, 3]] * 3)
    assert sim.AddClumps(tmpl, np.zeros((0, 3))).GetNumClumps() == 0
    assert sim.AddClumps([tmpl, tmpl], [[0.3, 0, 0], [0.4, 0, 0]]).GetNumClumps() == 2


def test_batch_keeps_a_shared_value_once(sim):
    """A value every clump shares is kept once; the getters give one row per clump all the same."""
    mat = material(sim)
    sim.InstructBoxDomainDimension(1, 1, 1)
    tmpl = sim.LoadSphereType(1.0, 0.001, mat)
    n = 1000
    batch = sim.AddClumps(tmpl, [[0.0009 * (i % 100) - 0.45, 0.002 * (i // 100), 0] for i in range(n)])
    shared = batch.GetHostBytes()
    assert shared < n * 12 + 100  # positions, and one velocity, spin, orientation and family
    batch.SetVel([0, 0, -1])
    batch.SetFamily(2)
    assert batch.GetHostBytes() == shared
    np.testing.assert_array_equal(batch.GetVelocities(), [[0, 0, -1]] * n)
    np.testing.assert_array_equal(batch.GetFamilies(), [2] * n)
    sim.SetInitTimeStep(1e-5)
    sim.Initialize()
    np.testing.assert_allclose(sim.Track(batch).Velocities()[n - 1], [0, 0, -1])


def test_batch_arrays_go_to_the_solver_at_initialize(sim):
    """At Initialize the solver takes the batch's clumps; its getters of initial values are errors."""
    mat = material(sim)
    sim.InstructBoxDomainDimension(1, 1, 1)
    tmpl = sim.LoadSphereType(1.0, 0.01, mat)
    batch = sim.AddClumps(tmpl, [[0, 0, 0], [0.1, 0, 0]])
    assert batch.GetHostBytes() >= 2 * 12 + 41  # its positions, and the values all its clumps share
    sim.SetInitTimeStep(1e-5)
    sim.Initialize()
    assert batch.GetNumClumps() == 2
    assert batch.GetHostBytes() < 53  # freed: the template is all it keeps
    with pytest.raises(deme.Error, match=r"^DEMClumpBatch::GetPositions: the batch's clumps are in the solver's state"):
        batch.GetPositions()
    np.testing.assert_allclose(sim.Track(batch).Positions()[1], [0.1, 0, 0], atol=1e-6)


def test_batch_templates_once_each(sim):
    """A batch keeps each template once (GetDistinctTypes) and gives each clump's (GetType, GetTypes)."""
    mat = material(sim)
    small, large = sim.LoadSphereType(1.0, 0.01, mat), sim.LoadSphereType(2.0, 0.02, mat)
    batch = sim.AddClumps([large, small, large], [[0, 0, 0], [0.1, 0, 0], [0.2, 0, 0]])
    assert [t.mass for t in batch.GetTypes()] == [2.0, 1.0, 2.0]
    assert [t.mass for t in batch.GetDistinctTypes()] == [2.0, 1.0]
    assert batch.GetType(1).mass == 1.0
    with pytest.raises(deme.Error, match=r"^DEMClumpBatch::GetType: clump 3 of a batch of 3"):
        batch.GetType(3)
    # A batch of one template made directly: no per-clump list of templates behind it.
    one = deme.DEMClumpBatch(small, [[0, 0, 0], [0.1, 0, 0]])
    assert one.GetNumClumps() == 2 and [t.mass for t in one.GetTypes()] == [1.0, 1.0]
    assert len(one.GetDistinctTypes()) == 1
    with pytest.raises(deme.Error, match=r"^DEMClumpBatch: got 1 templates for 2 positions"):
        deme.DEMClumpBatch([small], [[0, 0, 0], [0.1, 0, 0]])


def test_clump_template_arrays(sim):
    mat = material(sim)
    radii = np.array([0.01, 0.02])
    rel = np.array([[0.01, 0, 0], [-0.005, 0, 0]])
    tmpl = sim.LoadClumpType(1.0, [1e-5, 2e-5, 3e-5], radii, rel, mat)
    assert tmpl.radii.dtype == np.float32 and tmpl.radii.shape == (2,)
    np.testing.assert_allclose(tmpl.relPos, rel, rtol=1e-6)
    assert tmpl.GetNumSpheres() == 2 and len(tmpl.materials) == 2
    np.testing.assert_allclose(tmpl.MOI, [1e-5, 2e-5, 3e-5], rtol=1e-6)
    two = sim.LoadClumpType(1.0, [1e-5, 1e-5, 1e-5], [0.01, 0.01], [[0.005, 0, 0], [-0.005, 0, 0]],
                            [mat, material(sim, CoR=0.3)])
    assert [m.GetLoadOrder() for m in two.materials] == [0, 1]


def test_mesh_from_arrays(sim):
    mat = material(sim)
    verts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    faces = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int64)
    mesh = deme.DEMMeshConnected(verts, faces, mat)
    assert mesh.GetNumTriangles() == 4 and mesh.GetNumVertices() == 4
    assert mesh.GetFaces().dtype == np.int32 and mesh.GetFaces().shape == (4, 3)
    np.testing.assert_array_equal(mesh.GetFaces(), faces)
    np.testing.assert_array_equal(mesh.GetVertices(), verts.astype(np.float32))
    mesh.Scale(2.0)
    np.testing.assert_array_equal(mesh.GetVertices(), 2 * verts.astype(np.float32))
    mesh.Scale([1, 2, 3])
    np.testing.assert_array_equal(mesh.GetVertices()[3], [0, 0, 6])
    added = sim.AddWavefrontMeshObject(mesh)
    assert added.GetNumTriangles() == 4
    # Faces from nested lists of ints work; floats are not silently truncated.
    assert deme.DEMMeshConnected(verts.tolist(), faces.tolist(), mat).GetNumTriangles() == 4
    with pytest.raises(TypeError, match="DEMMeshConnected"):
        deme.DEMMeshConnected(verts, faces.astype(float) + 0.5, mat)
    with pytest.raises(deme.Error, match="face 0 indexes a vertex outside 0..3"):
        deme.DEMMeshConnected(verts, [[0, 1, 9]], mat)


def test_single_vectors_in_and_out(sim):
    mat = material(sim)
    obj = sim.AddExternalObject()
    for pos in ([0, 0, 1], (0, 0, 1), np.array([0, 0, 1]), np.array([0, 0, 1], dtype=np.float32)):
        obj.AddPlane(pos, [0, 0, 1], mat)
    comps = obj.GetComponents()
    assert len(comps) == 4 and comps[0].type == deme.AnalyticalType.ANAL_PLANE
    out = comps[0].pos
    assert isinstance(out, np.ndarray) and out.dtype == np.float32 and out.shape == (3,)
    obj.SetInitQuat([0, 0, 0.7071068, 0.7071068])  # x, y, z, w: 90 degrees about z
    np.testing.assert_allclose(obj.GetInitQuat(), [0, 0, 0.7071068, 0.7071068], rtol=1e-6)
    sim.SetGravitationalAcceleration(np.array([0, 0, -9.81]))
    np.testing.assert_allclose(sim.GetGravitationalAcceleration(), [0, 0, -9.81], rtol=1e-6)
