"""The output calls from Python: VTU frames and their ParaView series read back by meshio, a PNG
snapshot decoded by PIL, the progress callback and the run summary."""
import os

import numpy as np
import pytest

import deme
from conftest import material, quiet_solver, sphere_mass


def falling_column(tmp_path):
    sim = quiet_solver()
    mat = material(sim, E=1e7)
    sim.InstructBoxDomainDimension(0.2, 0.2, 0.2)
    sim.InstructBoxDomainBoundingBC("top_open", mat)
    r = 0.005
    pts = deme.HCPSampler(2.01 * r).SampleBox([0, 0, -0.05], [0.03, 0.03, 0.03])
    batch = sim.AddClumps(sim.LoadSphereType(sphere_mass(r, 2600), r, mat), pts)
    sim.SetInitTimeStep(1e-5)
    sim.SetGravitationalAcceleration([0, 0, -9.81])
    sim.SetOutputFormat("VTU")
    sim.SetOutputContent(["ABSV", "VEL"])
    sim.SetOutputSeries("spheres", str(tmp_path / "spheres.pvd"))
    sim.Initialize()
    return sim, batch, len(pts)


def test_vtu_frames_and_series_read_back(tmp_path):
    meshio = pytest.importorskip("meshio")
    sim, batch, n = falling_column(tmp_path)
    tracker = sim.Track(batch)
    for frame in range(2):
        sim.DoDynamics(0.002)
        sim.WriteSphereFile(str(tmp_path / f"spheres_{frame}.vtu"))
        pos = tracker.Positions()
    sim.FlushOutput()
    m = meshio.read(str(tmp_path / "spheres_1.vtu"))
    assert m.points.shape == (n, 3)
    assert np.allclose(m.point_data["r"], 0.005)
    # One-sphere clumps: each sphere centre is its clump's position (float32 from the tracker).
    assert np.allclose(np.sort(m.points[:, 2]), np.sort(pos[:, 2]), rtol=0, atol=1e-6)
    assert np.allclose(np.sort(np.linalg.norm(m.point_data["v"], axis=1)), np.sort(m.point_data["absv"]), atol=1e-6)
    pvd = (tmp_path / "spheres.pvd").read_text()
    assert pvd.count("<DataSet") == 2 and "spheres_0.vtu" in pvd and "spheres_1.vtu" in pvd


def test_snapshot_png_has_the_requested_size(tmp_path):
    Image = pytest.importorskip("PIL.Image")
    sim, _, _ = falling_column(tmp_path)
    opts = deme.SnapshotOptions()
    opts.width, opts.height = 320, 200
    opts.colorBy = "height"
    opts.background = [10, 20, 30]
    sim.WriteSnapshot(str(tmp_path / "frame.png"), opts)
    sim.FlushOutput()
    with Image.open(tmp_path / "frame.png") as im:
        assert im.size == (320, 200)
        assert im.getpixel((1, 1))[:3] == (10, 20, 30)  # a corner is background


def test_progress_callback_and_run_summary(tmp_path):
    sim, _, n = falling_column(tmp_path)
    seen = []
    sim.SetProgressCallback(lambda p: seen.append((p.stepsDone, p.stepsTotal, p.finished)))
    sim.DoDynamics(0.01)  # 1000 steps
    assert seen and seen[-1] == (1000, 1000, True)
    summary = sim.GetRunSummary()
    assert summary.steps == 1000 and summary.spheres == n and summary.sphereStepsPerSecond > 0


def test_progress_callback_exception_stops_the_call(tmp_path):
    sim, _, _ = falling_column(tmp_path)

    def fail(p):
        raise ValueError("stop here")

    sim.SetProgressCallback(fail)
    with pytest.raises(ValueError, match="stop here"):
        sim.DoDynamics(1.0)  # 10^5 steps: stopped at a step boundary long before
    assert 0 < sim.GetSimTime() < 1.0
    sim.SetProgressCallback(None)
    t = sim.GetSimTime()
    sim.DoDynamics(0.001)
    assert abs(sim.GetSimTime() - (t + 0.001)) < 1e-9


def test_bad_output_settings_are_deme_errors(sim):
    with pytest.raises(deme.Error, match="SetOutputFormat"):
        sim.SetOutputFormat("XLSX")
    with pytest.raises(deme.Error, match="SetVTUEncoding"):
        sim.SetVTUEncoding("hex")


def test_compressed_base64_vtu_and_progress_report_switch(tmp_path):
    meshio = pytest.importorskip("meshio")
    sim, _, n = falling_column(tmp_path)
    sim.SetVTUEncoding("base64")
    sim.SetVTUCompression("zlib")
    sim.SetProgressReport(False)
    sim.SetProgressReport(True, 1.0)
    sim.WriteSphereFile(str(tmp_path / "packed.vtu"))
    sim.FlushOutput()
    m = meshio.read(str(tmp_path / "packed.vtu"))
    assert m.points.shape == (n, 3) and np.allclose(m.point_data["r"], 0.005)
