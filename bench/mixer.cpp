// MIXER-BENCH (../shared/bench/README.md): the paper's mixer scaling test at a fixed size.
//   mixer <internal_mixer.obj> <r> [spheres|clumps] [warm steps] [timed steps] [warm-up dt] [gpus]
//         [auto|sync|async]
// The timed steps always use dt = 5e-7. The warm-up may use a coarser step: the settled variant,
// with the grains landed on the floor and in contact, is 125000 warm-up steps of 2e-6 (0.25 s of
// mixing; the grains fall about 0.3 m first, so after the README's 0.05 s none touch yet).
// gpus: 1 (default) runs dynamics and contact detection on one GPU, 2 puts detection on a second
// GPU (DEMSolver(2)); the last argument selects the contact detection mode (default auto:
// asynchronous where the CPU has 8 or more cores).
// DEME_BENCH_TIMING=1 adds the timing and collaboration reports. Prints one JSON line: sphere-steps/s over the timed
// steps, contacts per sphere, n_max, dynamics wait share, device bytes per sphere, and how long Initialize() took (run
// twice for cold and warm: the second run finds the kernels in the cache). MIXER_ORDER=columns gives the grains to
// AddClumps in columns of 16 spacings across (ColumnOrder.h) instead of the sampler's layers: what the grains' order
// costs the steps at scale ("order" in the JSON).
#include <deme/deme.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "BenchUtil.h"
#include "ColumnOrder.h"

using namespace deme;

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr,
                     "usage: %s <internal_mixer.obj> <r> [spheres|clumps] [warm] [steps] [warm dt] [gpus] "
                     "[auto|sync|async]\n",
                     argv[0]);
        return 2;
    }
    const std::string obj = argv[1];
    const double r = std::atof(argv[2]);
    const bool clumps = argc > 3 && std::string(argv[3]) == "clumps";
    const unsigned long warm = argc > 4 ? std::strtoul(argv[4], nullptr, 10) : 2000;
    const unsigned long steps = argc > 5 ? std::strtoul(argv[5], nullptr, 10) : 2000;
    const double dt = 5e-7, density = 2600.0;
    const double warmDt = argc > 6 ? std::atof(argv[6]) : dt;
    const unsigned long gpus = argc > 7 ? std::strtoul(argv[7], nullptr, 10) : 1;
    const std::string mode = argc > 8 ? argv[8] : "auto";
    if (gpus < 1 || (mode != "auto" && mode != "sync" && mode != "async")) {
        std::fprintf(stderr, "gpus must be 1 or more, the mode auto, sync or async\n");
        return 2;
    }

    DEMSolver sim((unsigned int)gpus);
    sim.SetVerbosity("WARNING");
    auto mat = sim.LoadMaterial({{"E", 1e9}, {"nu", 0.3}, {"CoR", 0.2}, {"mu", 0.5}, {"Crr", 0.0}});
    sim.InstructBoxDomainDimension(1, 1, 1);
    sim.InstructBoxDomainBoundingBC("all", mat);
    auto drum = sim.AddExternalObject();
    drum->AddCylinder(make_float3(0), make_float3(0, 0, 1), 0.5f, mat, 0);

    // The mixer: scaled by (0.5, 0.5, 1/3), centred at z = -0.5 + 1/6, turning at 2 pi rad/s. Its arms
    // reach past the cylinder and the box: meshes are not bounded by the domain.
    auto mixer = sim.AddWavefrontMeshObject(obj, mat);
    mixer->Scale(make_float3(0.5f, 0.5f, 1.f / 3.f));
    mixer->SetFamily(10);
    mixer->SetInitPos(make_float3(0, 0, -0.5f + 1.f / 6.f));
    sim.SetFamilyPrescribedAngVel(10, "0", "0", "2*pi");

    std::shared_ptr<DEMClumpTemplate> grain;
    float spacing;
    if (clumps) {
        const double r3 = r * r * r, r5 = r3 * r * r;
        grain = sim.LoadClumpType((float)(density * 5.5886717 * r3),
                                  make_float3(2.928f, 2.6029f, 3.9908f) * (float)(density * r5),
                                  std::vector<float>(3, 0.8f * (float)r),
                                  {make_float3(0.5f, 0.341729f, 0.f) * (float)r, make_float3(0.f, -0.658271f, 0.f) * (float)r,
                                   make_float3(-0.5f, 0.341729f, 0.f) * (float)r},
                                  mat);
        spacing = 3.f * (float)r;
    } else {
        grain = sim.LoadSphereType((float)(density * 4.0 / 3.0 * PI * r * r * r), (float)r, mat);
        spacing = 2.002f * (float)r;
    }
    HCPSampler sampler(spacing);
    auto xyz = sampler.SampleCylinderZ(make_float3(0, 0, -0.5f + 1.f / 3.f + 1.f / 6.f), 0.5f - 2.f * (float)r,
                                       1.f / 6.f);
    const char* order = std::getenv("MIXER_ORDER");
    const bool columns = order && std::string(order) == "columns";
    if (order && !columns && std::string(order) != "sampler") {
        std::fprintf(stderr, "MIXER_ORDER must be sampler or columns\n");
        return 2;
    }
    if (columns) deme_bench::orderInColumns(xyz, 16.f * spacing);
    sim.AddClumps(grain, xyz);
    std::vector<float3>().swap(xyz);  // the batch has its copy: the peak is the engine's alone
    sim.SetInitTimeStep(dt);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetCDUpdateFreq(20);
    sim.SetMaxVelocity(5.f);  // the blade tips move at about 4.7 m/s
    if (mode != "auto") sim.SetSynchronousContactDetection(mode == "sync");

    const double t0 = deme_bench::seconds();
    sim.Initialize();
    const double initSeconds = deme_bench::seconds() - t0;
    sim.UpdateStepSize(warmDt);
    sim.DoDynamics((double)warm * warmDt);
    sim.UpdateStepSize(dt);
    const double t1 = deme_bench::seconds();
    sim.DoDynamics((double)steps * dt);
    const double wall = deme_bench::seconds() - t1;
    const double spheres = (double)sim.GetNumSpheres();

    deme_bench::JsonLine j;
    j.add("case", "MIXER-BENCH")
        .add("size_r", r)
        .add("grains", clumps ? "3-sphere clumps" : "spheres")
        .add("backend", sim.GetBackend())
        .add("clumps", (double)sim.GetNumClumps())
        .add("spheres", spheres)
        .add("contacts_per_sphere", sim.GetAvgSphContacts())
        .add("contacts_total", (double)sim.GetNumContacts())  // with walls and the mixer
        .add("warmup_s", (double)warm * warmDt)
        .add("steps", (double)steps)
        .add("wall_s", wall)
        .add("sphere_steps_per_s", spheres * (double)steps / wall)
        .add("gpus", (double)gpus)
        .add("detection", sim.UsesAsyncContactDetection() ? "async" : "sync")
        .add("update_freq", (double)sim.GetUpdateFreq())
        .add("dT_wait_share", sim.GetDynamicsWaitShare())
        .add("async_updates", (double)sim.GetNumAsyncContactSetUpdates())
        .add("device_bytes_per_sphere", (double)sim.GetDeviceMemUsage() / spheres)
        .add("peak_host_mem_mib", deme_bench::peakMemoryMiB())
        .add("initialize_s", initSeconds)
        .add("order", columns ? "columns" : "sampler");
    deme_bench::addRunSummary(j, sim.GetRunSummary());
    deme_bench::addMemoryStats(j, sim.GetMemoryStats());
    std::printf("%s\n", j.str().c_str());
    // The phases (binning and pair search are kT's, history mapping and the force pass dT's) and the
    // collaboration counters, for a case whose wait share needs explaining.
    if (std::getenv("DEME_BENCH_TIMING")) {
        sim.ShowMemoryStats();
        sim.ShowTimingStats();
        sim.ShowThreadCollaborationStats();
    }
    return 0;
}
