// CPU-BED benchmark (../shared/bench/README.md): 60,000 settled spheres in a box, the same model,
// materials and time step as the LIGGGHTS reference input. Prints one JSON line.
//   usage: cpu_bed [bed60k.csv] [warm-up steps] [timed steps] [auto|sync|async] [builtin|custom]
// "custom" runs the default model written out as a custom model (compiled at run time), to compare
// the run-time compiled force loop with the built-in one.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <vector>

#include <deme/deme.h>

#include "BenchUtil.h"
#include "HertzMindlinSnippet.h"

using namespace deme;
using namespace deme_bench;

namespace {

struct Bed {
    std::vector<float3> pos;
    float radius = 0.f;
};

Bed readBed(const std::string& path) {
    std::ifstream f(path);
    if (!f) throw Error("cpu_bed: cannot open " + path);
    Bed bed;
    std::string line;
    std::getline(f, line);  // header x,y,z,r
    while (std::getline(f, line)) {
        if (line.empty()) continue;
        std::istringstream is(line);
        float x, y, z, r;
        char c;
        is >> x >> c >> y >> c >> z >> c >> r;
        bed.pos.push_back(make_float3(x, y, z));
        bed.radius = r;
    }
    return bed;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string path = argc > 1 ? argv[1] : DEME_SHARED_BENCH_DIR "/bed60k.csv";
    const int warm = argc > 2 ? std::atoi(argv[2]) : 200;
    const int steps = argc > 3 ? std::atoi(argv[3]) : 2000;
    // "sync" or "async" forces the contact-detection mode; default: the engine's choice (AUTO).
    const std::string mode = argc > 4 ? argv[4] : "auto";
    const bool custom = argc > 5 && std::string(argv[5]) == "custom";
    const double density = 2600, g = 9.81;

    const double t0 = seconds();
    const Bed bed = readBed(path);
    DEMSolver sim;
    sim.SetVerbosity("WARNING");
    auto mat = sim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}});
    if (custom) deme_bench::useHertzMindlinSnippet(sim);
    sim.InstructBoxDomainDimension({-0.01f, 0.11f}, {-0.01f, 0.11f}, {-0.01f, 0.2f});
    auto walls = sim.AddExternalObject();
    walls->AddPlane(make_float3(0, 0, 0), make_float3(1, 0, 0), mat);
    walls->AddPlane(make_float3(0.1f, 0, 0), make_float3(-1, 0, 0), mat);
    walls->AddPlane(make_float3(0, 0, 0), make_float3(0, 1, 0), mat);
    walls->AddPlane(make_float3(0, 0.1f, 0), make_float3(0, -1, 0), mat);
    auto floorObj = sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    const double r = bed.radius;
    const double m = density * 4.0 / 3.0 * PI * r * r * r;
    sim.AddClumps(sim.LoadSphereType((float)m, (float)r, mat), bed.pos);
    sim.SetInitTimeStep(5e-6);
    if (mode != "auto") sim.SetSynchronousContactDetection(mode == "sync");
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-g));
    sim.Initialize();
    auto floorTracker = sim.Track(floorObj);
    const double setup = seconds() - t0;

    for (int i = 0; i < warm; i++) sim.DoStepDynamics();
    // Time the stepping alone; the floor force is averaged over the timed steps (reading it after
    // each step is a few field reads, negligible next to a step).
    double floorSum = 0.0;
    const double t1 = seconds();
    for (int i = 0; i < steps; i++) {
        sim.DoStepDynamics();
        floorSum += -floorTracker->ContactForce().z;
    }
    const double wall = seconds() - t1;

    const double weight = (double)bed.pos.size() * m * g;
    const double floorForce = floorSum / steps;
    JsonLine j;
    j.add("case", "CPU-BED")
        .add("size", (double)bed.pos.size())
        .add("backend", sim.UsesAsyncContactDetection() ? "cpu-async" : "cpu-sync")
        .add("model", custom ? "custom (Hertz-Mindlin as a snippet)" : "built-in")
        .add("device", cpuName() + " x " + std::to_string(std::thread::hardware_concurrency()) + " threads")
        .add("spheres", (double)sim.GetNumSpheres())
        .add("contacts_per_sphere", sim.GetAvgSphContacts())
        .add("steps", (double)steps)
        .add("wall_s", wall)
        .add("sphere_steps_per_s", (double)sim.GetNumSpheres() * steps / wall)
        .add("peak_mem_mib", peakMemoryMiB())
        .add("setup_s", setup)
        .add("floor_force_avg_N", floorForce)
        .add("weight_N", weight)
        .add("floor_over_weight", floorForce / weight)
        .add("update_freq", (double)sim.GetUpdateFreq());
    addRunSummary(j, sim.GetRunSummary());
    std::cout << j.str() << std::endl;
    if (std::getenv("DEME_BENCH_TIMING")) {
        sim.ShowTimingStats();
        sim.ShowThreadCollaborationStats();
    }
    return 0;
}
