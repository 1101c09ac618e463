"""Run by a fresh interpreter that sees only an installed deme package (test_installed.py after
`cmake --install`, pip_install_test.sh after pip): imports deme and DEME, finds the data files,
runs a small simulation with them, and prints what it found for the caller to check."""
import os

import deme
import DEME

assert DEME is deme
print("module", os.path.abspath(deme.__file__))
print("mesh", deme.GetDEMEDataFile("mesh/internal_mixer.obj"))
print("clump", deme.GetDEMEDataFile("clumps/3_clump.csv"))
sim = deme.DEMSolver()
sim.SetVerbosity("QUIET")
mat = sim.LoadMaterial({"E": 1e8, "nu": 0.3, "CoR": 0.5, "mu": 0.5})
sim.InstructBoxDomainDimension(1, 1, 1)
sim.AddWavefrontMeshObject(deme.GetDEMEDataFile("mesh/internal_mixer.obj"), mat).Scale(0.1)
tmpl = sim.LoadClumpType(2.6e3 * 5.5886717, [2.928 * 2.6e3, 2.6029 * 2.6e3, 3.9908 * 2.6e3],
                         deme.GetDEMEDataFile("clumps/3_clump.csv"), mat)
tmpl.Scale(0.01)
batch = sim.AddClumps(tmpl, [[0, 0, 0.3], [0.1, 0, 0.3]])
sim.SetInitTimeStep(1e-5)
sim.SetGravitationalAcceleration([0, 0, -9.81])
sim.Initialize()
sim.DoDynamics(0.01)
print("z", float(sim.Track(batch).Positions()[0, 2]))
