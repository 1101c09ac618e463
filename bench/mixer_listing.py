#!/usr/bin/python3
"""MIXER-LISTING, Python side: the paper's §4.2 listing frame by frame, the same scene, frames and
per-frame calls as bench/mixer_listing.cpp (see there), through the Python module. Prints the
listing's lines, then one JSON line. bench/python_vs_cpp.sh runs both back to back.

  PYTHONPATH=build/python /usr/bin/python3 bench/mixer_listing.py <output dir> [granular_rad] [step] [frames]
"""
import json
import os
import sys
import time

import numpy as np

import DEME


def cpu_name():
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return "unknown CPU"


if __name__ == "__main__":
    out_dir = sys.argv[1]
    granular_rad = float(sys.argv[2]) if len(sys.argv) > 2 else 0.02
    step_size = float(sys.argv[3]) if len(sys.argv) > 3 else 2e-5
    frames = int(sys.argv[4]) if len(sys.argv) > 4 else 6
    os.makedirs(out_dir, exist_ok=True)

    DEMSim = DEME.DEMSolver()
    DEMSim.SetVerbosity("STEP_METRIC")
    DEMSim.SetOutputFormat("CSV")
    DEMSim.SetOutputContent(["ABSV", "XYZ"])
    DEMSim.SetMeshOutputFormat("VTK")
    mat_type_mixer = DEMSim.LoadMaterial({"E": 1e8, "nu": 0.3, "CoR": 0.6, "mu": 0.5, "Crr": 0.0})
    mat_type_granular = DEMSim.LoadMaterial({"E": 1e8, "nu": 0.3, "CoR": 0.8, "mu": 0.2, "Crr": 0.0})
    DEMSim.SetMaterialPropertyPair("CoR", mat_type_mixer, mat_type_granular, 0.5)

    world_size = 1
    chamber_height = world_size / 3.
    fill_height = chamber_height
    chamber_bottom = -world_size / 2.
    fill_bottom = chamber_bottom + chamber_height
    DEMSim.InstructBoxDomainDimension(world_size, world_size, world_size)
    DEMSim.InstructBoxDomainBoundingBC("all", mat_type_granular)
    walls = DEMSim.AddExternalObject()
    walls.AddCylinder([0, 0, 0], [0, 0, 1], world_size / 2., mat_type_mixer, 0)

    mixer = DEMSim.AddWavefrontMeshObject(DEME.GetDEMEDataFile("mesh/internal_mixer.obj"), mat_type_mixer)
    print(f"Total num of triangles: {mixer.GetNumTriangles()}")
    mixer.Scale([world_size / 2, world_size / 2, chamber_height])
    mixer.SetFamily(10)
    DEMSim.SetFamilyPrescribedAngVel(10, "0", "0", "3.14159")
    mixer_tracker = DEMSim.Track(mixer)

    mass = 2.6e3 * 5.5886717
    MOI = np.array([2.928, 2.6029, 3.9908]) * 2.6e3
    template_granular = DEMSim.LoadClumpType(mass, MOI.tolist(), DEME.GetDEMEDataFile("clumps/3_clump.csv"),
                                             mat_type_granular)
    template_granular.Scale(granular_rad)
    sampler = DEME.HCPSampler(3.0 * granular_rad)
    fill_center = [0, 0, fill_bottom + fill_height / 2]
    fill_radius = world_size / 2. - 2. * granular_rad
    input_xyz = sampler.SampleCylinderZ(fill_center, fill_radius, fill_height / 2)
    DEMSim.AddClumps(template_granular, input_xyz)
    print(f"Total num of particles: {len(input_xyz)}")

    DEMSim.SetInitTimeStep(step_size)
    DEMSim.SetGravitationalAcceleration([0, 0, -9.81])
    DEMSim.SetErrorOutVelocity(20.)
    DEMSim.SetForceCalcThreadsPerBlock(512)
    DEMSim.Initialize()

    frame_time = 1.0 / 20
    max_v_finder = DEMSim.CreateInspector("clump_max_absv")
    mixer_tracker.SetPos([0, 0, chamber_bottom + chamber_height / 2.0])

    in_dynamics = 0.0
    loop_start, cpu_start = time.perf_counter(), time.process_time()
    for currframe in range(frames):
        print(f"Frame: {currframe}", flush=True)
        DEMSim.WriteSphereFile(os.path.join(out_dir, f"DEMdemo_output_{currframe:04d}.csv"))
        DEMSim.WriteMeshFile(os.path.join(out_dir, f"DEMdemo_mesh_{currframe:04d}.vtk"))
        max_v = max_v_finder.GetValue()
        print(f"Max velocity of any point in simulation is {max_v}", flush=True)
        print(f"Solver's current update frequency (auto-adapted): {DEMSim.GetUpdateFreq()}", flush=True)
        print(f"Average contacts each sphere has: {DEMSim.GetAvgSphContacts()}", flush=True)
        mixer_moi = np.array(mixer_tracker.MOI())
        mixer_acc = np.array(mixer_tracker.ContactAngAccLocal())
        mixer_torque = np.cross(mixer_acc, mixer_moi)
        print(f"Contact torque on the mixer is {mixer_torque[0]}, {mixer_torque[1]}, {mixer_torque[2]}", flush=True)
        t0 = time.perf_counter()
        DEMSim.DoDynamics(frame_time)
        in_dynamics += time.perf_counter() - t0
        DEMSim.ShowThreadCollaborationStats()
    loop, loop_cpu = time.perf_counter() - loop_start, time.process_time() - cpu_start
    print(json.dumps({"bench": "mixer_listing", "lang": "python", "backend": DEMSim.GetBackend(), "device": cpu_name(),
                      "clumps": DEMSim.GetNumClumps(), "spheres": DEMSim.GetNumSpheres(), "frames": frames,
                      "steps": round(DEMSim.GetSimTime() / step_size), "loop_s": loop, "loop_cpu_s": loop_cpu, "dodynamics_s": in_dynamics,
                      "outside_dodynamics_s": loop - in_dynamics, "final_max_v": max_v_finder.GetValue(),
                      "final_contacts": DEMSim.GetNumContacts()}))
