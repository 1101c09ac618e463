// MIXER-LISTING, C++ side: the paper's mixer listing (§4.1 / §4.2) as one program, frame by frame
// (one DoDynamics per frame, with the listing's per-frame output and queries), for comparison with
// bench/mixer_listing.py, the same scene and frames through the Python module
// (bench/python_vs_cpp.sh runs both back to back). Prints the listing's lines, then one JSON line.
//   mixer_listing <output dir> [granular_rad = 0.02] [step = 2e-5] [frames = 6]
// The listing's 0.005 m grains (105,000 clumps) are days of CPU time; 0.02 m gives 1,450 clumps,
// and the step grows with them (2e-5 s is 4.5 % of their spheres' Rayleigh time, the listing's
// share at its size).
#include <deme/deme.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <time.h>

#include "BenchUtil.h"

using namespace deme;

namespace {
// CPU time of the process (all threads), as Python's time.process_time().
double cpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s <output dir> [granular_rad] [step] [frames]\n", argv[0]);
        return 2;
    }
    const std::filesystem::path out_dir = argv[1];
    // Doubles, converted to float at each call, as the Python script's floats are: both programs
    // then give the engine the very same numbers and run the very same simulation.
    const double granular_rad = argc > 2 ? std::strtod(argv[2], nullptr) : 0.02;
    const double step_size = argc > 3 ? std::strtod(argv[3], nullptr) : 2e-5;
    const int frames = argc > 4 ? std::atoi(argv[4]) : 6;
    std::filesystem::create_directories(out_dir);

    DEMSolver DEMSim;
    DEMSim.SetVerbosity("STEP_METRIC");
    DEMSim.SetOutputFormat("CSV");
    DEMSim.SetOutputContent(std::vector<std::string>{"ABSV", "XYZ"});
    DEMSim.SetMeshOutputFormat("VTK");
    auto mat_type_mixer = DEMSim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.6}, {"mu", 0.5}, {"Crr", 0.0}});
    auto mat_type_granular = DEMSim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.8}, {"mu", 0.2}, {"Crr", 0.0}});
    DEMSim.SetMaterialPropertyPair("CoR", mat_type_mixer, mat_type_granular, 0.5);

    const double world_size = 1;
    const double chamber_height = world_size / 3.;
    const double fill_height = chamber_height;
    const double chamber_bottom = -world_size / 2.;
    const double fill_bottom = chamber_bottom + chamber_height;
    DEMSim.InstructBoxDomainDimension(world_size, world_size, world_size);
    DEMSim.InstructBoxDomainBoundingBC("all", mat_type_granular);
    auto walls = DEMSim.AddExternalObject();
    walls->AddCylinder(make_float3(0, 0, 0), make_float3(0, 0, 1), world_size / 2., mat_type_mixer, 0);

    auto mixer = DEMSim.AddWavefrontMeshObject(GetDEMEDataFile("mesh/internal_mixer.obj"), mat_type_mixer);
    std::printf("Total num of triangles: %zu\n", mixer->GetNumTriangles());
    mixer->Scale(make_float3(world_size / 2, world_size / 2, chamber_height));
    mixer->SetFamily(10);
    DEMSim.SetFamilyPrescribedAngVel(10, "0", "0", "3.14159");
    auto mixer_tracker = DEMSim.Track(mixer);

    const double mass = 2.6e3 * 5.5886717;
    const float3 MOI = make_float3(2.928 * 2.6e3, 2.6029 * 2.6e3, 3.9908 * 2.6e3);
    auto template_granular =
        DEMSim.LoadClumpType(mass, MOI, GetDEMEDataFile("clumps/3_clump.csv"), mat_type_granular);
    template_granular->Scale(granular_rad);
    HCPSampler sampler(3.0 * granular_rad);
    const float3 fill_center = make_float3(0, 0, fill_bottom + fill_height / 2);
    const double fill_radius = world_size / 2. - 2. * granular_rad;
    auto input_xyz = sampler.SampleCylinderZ(fill_center, fill_radius, fill_height / 2);
    DEMSim.AddClumps(template_granular, input_xyz);
    std::printf("Total num of particles: %zu\n", input_xyz.size());

    DEMSim.SetInitTimeStep(step_size);
    DEMSim.SetGravitationalAcceleration(make_float3(0, 0, -9.81));
    DEMSim.SetErrorOutVelocity(20.);
    DEMSim.SetForceCalcThreadsPerBlock(512);
    DEMSim.Initialize();

    const double frame_time = 1.0 / 20;
    auto max_v_finder = DEMSim.CreateInspector("clump_max_absv");
    mixer_tracker->SetPos(make_float3(0, 0, chamber_bottom + chamber_height / 2.0));

    double in_dynamics = 0.0, max_v = 0.0;
    const double loop_start = deme_bench::seconds(), cpu_start = cpuSeconds();
    for (int currframe = 0; currframe < frames; currframe++) {
        std::printf("Frame: %d\n", currframe);
        std::fflush(stdout);
        char filename[64], meshname[64];
        std::snprintf(filename, sizeof(filename), "DEMdemo_output_%04d.csv", currframe);
        std::snprintf(meshname, sizeof(meshname), "DEMdemo_mesh_%04d.vtk", currframe);
        DEMSim.WriteSphereFile((out_dir / filename).string());
        DEMSim.WriteMeshFile((out_dir / meshname).string());
        max_v = max_v_finder->GetValue();
        std::printf("Max velocity of any point in simulation is %g\n", max_v);
        std::printf("Solver's current update frequency (auto-adapted): %u\n", DEMSim.GetUpdateFreq());
        std::printf("Average contacts each sphere has: %g\n", DEMSim.GetAvgSphContacts());
        const float3 mixer_moi = mixer_tracker->MOI();
        const float3 mixer_acc = mixer_tracker->ContactAngAccLocal();
        const float3 mixer_torque = cross(mixer_acc, mixer_moi);  // the listing's np.cross
        std::printf("Contact torque on the mixer is %g, %g, %g\n", mixer_torque.x, mixer_torque.y, mixer_torque.z);
        std::fflush(stdout);
        const double t0 = deme_bench::seconds();
        DEMSim.DoDynamics(frame_time);
        in_dynamics += deme_bench::seconds() - t0;
        DEMSim.ShowThreadCollaborationStats();
    }
    const double loop = deme_bench::seconds() - loop_start, loop_cpu = cpuSeconds() - cpu_start;
    std::printf("%s\n", deme_bench::JsonLine()
                            .add("bench", "mixer_listing")
                            .add("lang", "cpp")
                            .add("backend", DEMSim.GetBackend())
                            .add("device", deme_bench::cpuName())
                            .add("clumps", (double)DEMSim.GetNumClumps())
                            .add("spheres", (double)DEMSim.GetNumSpheres())
                            .add("frames", (double)frames)
                            .add("steps", DEMSim.GetSimTime() / step_size)
                            .add("loop_s", loop)
                            .add("loop_cpu_s", loop_cpu)
                            .add("dodynamics_s", in_dynamics)
                            .add("outside_dodynamics_s", loop - in_dynamics)
                            .add("final_max_v", max_v_finder->GetValue())
                            .add("final_contacts", (double)DEMSim.GetNumContacts())
                            .str()
                            .c_str());
    return 0;
}
