"""The paper's §4.2 Python listing (demos/python/mixer.py, run as written with a shortened end
time) and the module's face: `import DEME`, help() and signatures."""
import os
import pydoc
import subprocess
import sys

import numpy as np

import deme
from conftest import package_env

SOURCE = os.environ.get("DEME_TEST_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
DEMO = os.path.join(SOURCE, "demos", "python", "mixer.py")


def test_import_DEME_is_the_same_module():
    import DEME

    assert DEME is deme
    assert DEME.DEMSolver is deme.DEMSolver
    assert isinstance(deme.__version__, str) and deme.__version__.count(".") == 2


def test_help_shows_signature_and_doc():
    text = pydoc.render_doc(deme.DEMSolver.AddClumps, renderer=pydoc.plaintext)
    assert "AddClumps(self: deme._deme.DEMSolver, type: deme._deme.DEMClumpTemplate, positions: Float3Array)" in text
    assert "Clumps of one template at positions (N, 3); returns the batch." in text
    # Every public method carries a one-line doc after its signature.
    for cls in (deme.DEMSolver, deme.DEMTracker, deme.DEMClumpBatch, deme.DEMMeshConnected, deme.DEMExternObj,
                deme.DEMClumpTemplate, deme.DEMForceModel, deme.HCPSampler, deme.GridSampler, deme.DEMInspector,
                deme.DEMMaterial):
        for name, fn in vars(cls).items():
            if name.startswith("_") or not callable(fn) or isinstance(fn, type):
                continue
            doc = fn.__doc__ or ""
            lines = [l for l in doc.split("\n") if l.strip()]
            assert len(lines) >= 2, "%s.%s has no doc line" % (cls.__name__, name)


def test_the_listing_runs_as_written(tmp_path):
    # --quick: the listing's end time shortened to two steps (the script's only change).
    res = subprocess.run([sys.executable, DEMO, "--quick"], cwd=tmp_path, env=package_env(),
                         capture_output=True, text=True, timeout=240)
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:]
    out = res.stdout
    assert "Total num of triangles: 176" in out
    n = int(out.split("Total num of particles: ")[1].split()[0])
    # HCP at spacing 3 r = 0.015 m in a cylinder of radius 0.49 m and height 1/3 m: the lattice's
    # density sqrt(2) / spacing^3 times the volume, within 5 % (boundary layers).
    expected = np.sqrt(2) / 0.015 ** 3 * np.pi * 0.49 ** 2 / 3
    assert abs(n - expected) < 0.05 * expected
    assert "Frame: 0" in out and "Contact torque on the mixer is" in out
    assert "seconds (wall time) to finish this simulation" in out
    csv = tmp_path / "DemoOutput_Mixer" / "DEMdemo_output_0000.csv"
    vtk = tmp_path / "DemoOutput_Mixer" / "DEMdemo_mesh_0000.vtk"
    with open(csv) as f:
        header = f.readline().strip()
        rows = sum(1 for _ in f)
    assert header == "X,Y,Z,r,absv"
    assert rows == 3 * n  # three spheres per clump
    assert vtk.stat().st_size > 0


def test_the_listing_calls_from_here(tmp_path):
    # The listing's calls in this process, on a coarser grain (fewer clumps), to read back what
    # they did: the scaled mesh, the clump template, the mixer's place and its prescribed spin.
    sim = deme.DEMSolver()
    sim.SetVerbosity("ERROR")
    sim.SetOutputFormat("CSV")
    sim.SetOutputContent(["ABSV", "XYZ"])
    sim.SetMeshOutputFormat("VTK")
    mat_mixer = sim.LoadMaterial({"E": 1e8, "nu": 0.3, "CoR": 0.6, "mu": 0.5, "Crr": 0.0})
    mat_gran = sim.LoadMaterial({"E": 1e8, "nu": 0.3, "CoR": 0.8, "mu": 0.2, "Crr": 0.0})
    sim.SetMaterialPropertyPair("CoR", mat_mixer, mat_gran, 0.5)
    world, chamber_h = 1, 1 / 3.0
    sim.InstructBoxDomainDimension(world, world, world)
    sim.InstructBoxDomainBoundingBC("all", mat_gran)
    walls = sim.AddExternalObject()
    walls.AddCylinder([0, 0, 0], [0, 0, 1], world / 2.0, mat_mixer, 0)
    mixer = sim.AddWavefrontMeshObject(deme.GetDEMEDataFile("mesh/internal_mixer.obj"), mat_mixer)
    mixer.Scale([world / 2, world / 2, chamber_h])
    v = mixer.GetVertices()
    assert v.dtype == np.float32 and v.shape == (mixer.GetNumVertices(), 3)
    assert np.hypot(v[:, 0], v[:, 1]).max() < 0.5 and abs(np.ptp(v[:, 2]) - 0.3) < 1e-5
    mixer.SetFamily(10)
    sim.SetFamilyPrescribedAngVel(10, "0", "0", "3.14159")
    tracker = sim.Track(mixer)
    rad = 0.02
    tmpl = sim.LoadClumpType(2.6e3 * 5.5886717, (np.array([2.928, 2.6029, 3.9908]) * 2.6e3).tolist(),
                             deme.GetDEMEDataFile("clumps/3_clump.csv"), mat_gran)
    tmpl.Scale(rad)
    assert abs(tmpl.mass - 2.6e3 * 5.5886717 * rad ** 3) < 1e-6 * tmpl.mass
    np.testing.assert_allclose(tmpl.MOI, np.array([2.928, 2.6029, 3.9908]) * 2.6e3 * rad ** 5, rtol=1e-5)
    np.testing.assert_allclose(tmpl.radii, [0.8 * rad] * 3, rtol=1e-6)
    xyz = deme.HCPSampler(3.0 * rad).SampleCylinderZ([0, 0, 0],
                                                      world / 2.0 - 2 * rad, chamber_h / 2 - 0.05)
    sim.AddClumps(tmpl, xyz)
    sim.SetInitTimeStep(2e-5)
    sim.SetGravitationalAcceleration([0, 0, -9.81])
    sim.SetErrorOutVelocity(20.0)
    sim.SetForceCalcThreadsPerBlock(512)
    sim.Initialize()
    max_v = sim.CreateInspector("clump_max_absv")
    tracker.SetPos([0, 0, -0.5 + chamber_h / 2.0])
    np.testing.assert_allclose(tracker.Pos(), [0, 0, -0.5 + chamber_h / 2.0], atol=1e-6)
    sim.DoDynamics(0.01)
    sim.ShowThreadCollaborationStats()
    assert sim.GetNumClumps() == len(xyz)
    assert max_v.GetValue() > 0.0 and sim.GetUpdateFreq() >= 1 and sim.GetAvgSphContacts() >= 0.0
    # The prescribed spin about the mesh's z axis: pi rad/s.
    np.testing.assert_allclose(tracker.AngVelGlobal(), [0, 0, 3.14159], rtol=1e-5, atol=1e-6)
    torque = np.array(tracker.ContactAngAccLocal()) * np.array(tracker.MOI())
    assert np.all(np.isfinite(torque))
    sim.WriteSphereFile(str(tmp_path / "s.csv"))
    sim.WriteMeshFile(str(tmp_path / "m.vtk"))
    sim.FlushOutput()  # files are written by the writer thread
    assert (tmp_path / "s.csv").stat().st_size > 0 and (tmp_path / "m.vtk").stat().st_size > 0
