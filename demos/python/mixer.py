# The paper's Python listing (§4.2): the bladed mixer of §4.1, run as written, with this engine's
# data files (data/mesh/internal_mixer.obj, data/clumps/3_clump.csv; GetDEMEDataFile finds them).
# Run it with Debian's interpreter after `bash scripts/setup.sh`:
#   PYTHONPATH=build/python /usr/bin/python3 demos/python/mixer.py [--quick]
# (or plain /usr/bin/python3 demos/python/mixer.py once the package is installed).
# The one change to the listing: its end time, 10 s (about 105,000 clumps, 2 million steps: days on
# a CPU), can be shortened, by --quick (two steps) or DEME_MIXER_SIM_END=<seconds>; a frame is
# then no longer than the run. Output goes to DemoOutput_Mixer/ in the working directory.
import DEME
import numpy as np
import os
import sys
import time


def shortened_end_time(sim_end, step_size):
    if "--quick" in sys.argv[1:]:
        return 2 * step_size
    return float(os.environ.get("DEME_MIXER_SIM_END", sim_end))


if __name__ == "__main__":
    out_dir = "DemoOutput_Mixer/"
    out_dir = os.path.join(os.getcwd(), out_dir)
    os.makedirs(out_dir, exist_ok=True)

    DEMSim = DEME.DEMSolver()
    DEMSim.SetVerbosity("STEP_METRIC")
    DEMSim.SetOutputFormat("CSV")
    DEMSim.SetOutputContent(["ABSV", "XYZ"])
    DEMSim.SetMeshOutputFormat("VTK")

    # E, nu, CoR, mu, Crr... Material properties
    mat_type_mixer = DEMSim.LoadMaterial(
        {"E": 1e8, "nu":  0.3, "CoR":  0.6, "mu":  0.5, "Crr": 0.0})
    mat_type_granular = DEMSim.LoadMaterial(
        {"E":  1e8, "nu":  0.3, "CoR":  0.8, "mu":  0.2, "Crr":  0.0})
    DEMSim.SetMaterialPropertyPair(
        "CoR", mat_type_mixer, mat_type_granular, 0.5)

    # Now define simulation world size and add the analytical boundary
    step_size = 5e-6
    world_size = 1
    chamber_height = world_size / 3.
    fill_height = chamber_height
    chamber_bottom = -world_size / 2.
    fill_bottom = chamber_bottom + chamber_height
    DEMSim.InstructBoxDomainDimension(world_size, world_size, world_size)
    DEMSim.InstructBoxDomainBoundingBC("all", mat_type_granular)
    walls = DEMSim.AddExternalObject()
    walls.AddCylinder([0, 0, 0], [0, 0, 1], world_size / 2., mat_type_mixer, 0)

    # Define the meshed mixer and its prescribed motion
    mixer = DEMSim.AddWavefrontMeshObject(
        DEME.GetDEMEDataFile("mesh/internal_mixer.obj"), mat_type_mixer)
    print(f"Total num of triangles: {mixer.GetNumTriangles()}")
    mixer.Scale([world_size / 2, world_size / 2, chamber_height])
    mixer.SetFamily(10)
    DEMSim.SetFamilyPrescribedAngVel(10, "0", "0", "3.14159")
    # Track the mixer
    mixer_tracker = DEMSim.Track(mixer)

    # Define the clump template used in the simulation
    granular_rad = 0.005
    mass = 2.6e3 * 5.5886717
    MOI = np.array([2.928, 2.6029, 3.9908]) * 2.6e3
    template_granular = DEMSim.LoadClumpType(mass, MOI.tolist(),
        DEME.GetDEMEDataFile("clumps/3_clump.csv"), mat_type_granular)
    template_granular.Scale(granular_rad)
    # Sampler uses hex close-packing
    sampler = DEME.HCPSampler(3.0 * granular_rad)
    fill_center = [0, 0, fill_bottom + fill_height / 2]
    fill_radius = world_size / 2. - 2. * granular_rad
    input_xyz = sampler.SampleCylinderZ(
        fill_center, fill_radius, fill_height / 2)
    DEMSim.AddClumps(template_granular, input_xyz)
    print(f"Total num of particles: {len(input_xyz)}")

    DEMSim.SetInitTimeStep(step_size)
    DEMSim.SetGravitationalAcceleration([0, 0, -9.81])
    DEMSim.SetErrorOutVelocity(20.)
    DEMSim.SetForceCalcThreadsPerBlock(512)
    DEMSim.Initialize()

    sim_end = shortened_end_time(10.0, step_size)
    fps = 20
    frame_time = min(1.0 / fps, sim_end)

    # Keep a tab of the max velocity in the simulation
    max_v_finder = DEMSim.CreateInspector("clump_max_absv")

    print(f"Output at {fps} FPS")
    currframe = 0

    mixer_tracker.SetPos([0, 0, chamber_bottom + chamber_height / 2.0])

    t = 0.
    start = time.process_time()
    while (t < sim_end):
        print(f"Frame: {currframe}", flush=True)
        filename = os.path.join(out_dir, f"DEMdemo_output_{currframe:04d}.csv")
        meshname = os.path.join(out_dir, f"DEMdemo_mesh_{currframe:04d}.vtk")
        DEMSim.WriteSphereFile(filename)
        DEMSim.WriteMeshFile(meshname)
        currframe += 1

        max_v = max_v_finder.GetValue()
        print(
            f"Max velocity of any point in simulation is {max_v}", flush=True)
        print(
            f"Solver's current update frequency (auto-adapted): {DEMSim.GetUpdateFreq()}", flush=True)
        print(
            f"Average contacts each sphere has: {DEMSim.GetAvgSphContacts()}", flush=True)

        mixer_moi = np.array(mixer_tracker.MOI())
        mixer_acc = np.array(mixer_tracker.ContactAngAccLocal())
        mixer_torque = np.cross(mixer_acc, mixer_moi)
        print(
            f"Contact torque on the mixer is {mixer_torque[0]}, {mixer_torque[1]}, {mixer_torque[2]}", flush=True)

        DEMSim.DoDynamics(frame_time)
        DEMSim.ShowThreadCollaborationStats()

        t += frame_time

    elapsed_time = time.process_time() - start
    print(f"{elapsed_time} seconds (wall time) to finish this simulation")
