"""The shipped data files: found through GetDEMEDataFile, equal to what scripts/make_data_files.py
makes, and the 3-sphere clump consistent with the mass properties of the paper's listing."""
import importlib.util
import os

import numpy as np
import pytest

import deme

SOURCE = os.environ.get("DEME_TEST_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def generator():
    spec = importlib.util.spec_from_file_location("make_data_files", os.path.join(SOURCE, "scripts",
                                                                                  "make_data_files.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_data_files_are_found_beside_the_module():
    path = deme.GetDEMEDataFile("mesh/internal_mixer.obj")
    package_dir = os.path.dirname(os.path.abspath(deme.__file__))
    # The package's own copy (deme/data), before the source tree's.
    assert path == os.path.join(package_dir, "data", "mesh", "internal_mixer.obj")
    assert os.path.isfile(deme.GetDEMEDataFile("clumps/3_clump.csv"))
    dirs = deme.GetDEMEDataDirs()
    assert os.path.join(package_dir, "data") in dirs


def test_data_dir_variable_comes_first(tmp_path, monkeypatch):
    (tmp_path / "mesh").mkdir()
    (tmp_path / "mesh" / "internal_mixer.obj").write_text("v 0 0 0\n")
    monkeypatch.setenv("DEME_DATA_DIR", str(tmp_path))
    assert deme.GetDEMEDataDirs()[0] == str(tmp_path)
    assert deme.GetDEMEDataFile("mesh/internal_mixer.obj") == str(tmp_path / "mesh" / "internal_mixer.obj")
    # Files it lacks are still found in the next folders.
    assert deme.GetDEMEDataFile("clumps/3_clump.csv").endswith(os.path.join("clumps", "3_clump.csv"))


def test_shipped_files_equal_the_generator_output():
    gen = generator()
    with open(deme.GetDEMEDataFile("mesh/internal_mixer.obj")) as f:
        assert f.read() == gen.mixer_obj_text()
    with open(deme.GetDEMEDataFile("clumps/3_clump.csv")) as f:
        assert f.read() == gen.clump_csv_text()


def test_three_sphere_clump_has_the_listings_mass_properties():
    # The listing loads clumps/3_clump.csv with mass = density * 5.5886717 and
    # MOI = density * (2.928, 2.6029, 3.9908), i.e. per unit density the volume and principal
    # moments of the union of its spheres (overlaps counted once), about its centre of mass.
    # Integrated on a grid here (midpoint rule, 240 cells across): 0.3 % on each.
    sim = deme.DEMSolver()
    sim.SetVerbosity("QUIET")
    mat = sim.LoadMaterial({"E": 1e8, "nu": 0.3, "CoR": 0.5, "mu": 0.5})
    tmpl = sim.LoadClumpType(5.5886717, [2.928, 2.6029, 3.9908], deme.GetDEMEDataFile("clumps/3_clump.csv"), mat)
    spheres = [tuple(p) + (r,) for p, r in zip(tmpl.relPos.tolist(), tmpl.radii.tolist())]
    assert len(spheres) == 3
    vol, com, moi = generator().union_mass_properties(spheres, n=240)
    assert abs(vol - 5.5886717) < 0.003 * 5.5886717
    assert np.abs(com).max() < 1e-3  # the file's frame is centred on the centre of mass
    np.testing.assert_allclose(moi, [2.928, 2.6029, 3.9908], rtol=0.003)
    # Principal frame: the products of inertia vanish by symmetry (all centres in z = 0, and the
    # clump is symmetric about x = 0).
    xs = [s[0] for s in spheres]
    assert sorted(xs) == sorted(-x for x in xs) and all(s[2] == 0 for s in spheres)


def test_mixer_mesh_fits_the_listings_chamber():
    sim = deme.DEMSolver()
    sim.SetVerbosity("QUIET")
    mat = sim.LoadMaterial({"E": 1e8, "nu": 0.3, "CoR": 0.5, "mu": 0.5})
    mixer = sim.AddWavefrontMeshObject(deme.GetDEMEDataFile("mesh/internal_mixer.obj"), mat)
    mixer.Scale([0.5, 0.5, 1 / 3.0])  # as the listing does
    v = mixer.GetVertices()
    # Inside the 0.5 m cylinder and the 1/3 m chamber, centred on its frame's origin (the listing
    # moves it to the chamber's middle with its tracker).
    assert np.hypot(v[:, 0], v[:, 1]).max() == pytest.approx(0.48, abs=1e-6)
    assert v[:, 2].min() == pytest.approx(-0.15, abs=1e-6) and v[:, 2].max() == pytest.approx(0.15, abs=1e-6)
