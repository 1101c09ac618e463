// DISCHARGE: a flat-bottomed hopper (demos/HopperGeometry.h) empties through its orifice under the
// "remove" exit policy: how fast the engine steps while grains leave (docs/scene-changes.md). The
// grains (r = 3 mm, 20 x 20 per layer) fall from a grid, are timed from the first grain's exit to
// the end, in frames of DoDynamics calls, and one JSON line gives steps per second and how many
// left.
//   discharge [cpu|cuda|auto] [layers] [timed seconds] [frame seconds]
#include <deme/deme.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "../demos/HopperGeometry.h"
#include "BenchUtil.h"

using namespace deme;

int main(int argc, char** argv) {
    const std::string backend = argc > 1 ? argv[1] : "cpu";
    const int layers = argc > 2 ? std::atoi(argv[2]) : 20;
    const double timed = argc > 3 ? std::atof(argv[3]) : 0.5;
    const double frame = argc > 4 ? std::atof(argv[4]) : 0.05;
    if ((backend != "cpu" && backend != "cuda" && backend != "auto") || layers < 1 || !(timed > 0) || !(frame > 0)) {
        std::fprintf(stderr, "usage: %s [cpu|cuda|auto] [layers] [timed seconds] [frame seconds]\n", argv[0]);
        return 2;
    }
    const double dt = 2e-5;
    DEMSolver sim;
    sim.SetVerbosity("WARNING");
    sim.SetBackend(backend);
    HopperSpec spec;
    spec.grainRadius = 0.003f;
    spec.spacing = 0.0095f;
    spec.nx = spec.ny = 20;
    spec.nz = layers;
    spec.domainTop = spec.floorZ + 2 * spec.grainRadius + layers * spec.spacing + 0.05f;
    buildHopper(sim, spec);
    sim.SetDomainExitPolicy("remove");
    sim.SetInitTimeStep(dt);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    const double t0 = deme_bench::seconds();
    sim.Initialize();
    const double initSeconds = deme_bench::seconds() - t0;
    const size_t grains = sim.GetNumClumps();
    // Until the first grain has left (the bottom layer falls 5 cm below the plate in about 0.1 s).
    while (sim.GetNumRemovedClumps() == 0 && sim.GetSimTime() < 1.0) sim.DoDynamics(0.01);
    const size_t before = sim.GetNumRemovedClumps();
    const double start = sim.GetSimTime();
    const double t1 = deme_bench::seconds();
    for (double t = 0; t < timed - 1e-9; t += frame) sim.DoDynamics(frame);
    const double wall = deme_bench::seconds() - t1;
    const double steps = (sim.GetSimTime() - start) / dt;
    const double left = (double)(sim.GetNumRemovedClumps() - before);

    deme_bench::JsonLine j;
    j.add("case", "DISCHARGE")
        .add("backend", sim.GetBackend())
        .add("device", sim.GetBackend() == "cpu" ? deme_bench::cpuName() : "GPU")
        .add("grains", (double)grains)
        .add("dt", dt)
        .add("frame_s", frame)
        .add("steps", steps)
        .add("wall_s", wall)
        .add("steps_per_s", steps / wall)
        .add("grains_left", left)
        .add("exits_per_sim_s", left / (sim.GetSimTime() - start))
        .add("detection", sim.UsesAsyncContactDetection() ? "async" : "sync")
        .add("initialize_s", initSeconds)
        .add("peak_host_mem_mib", deme_bench::peakMemoryMiB());
    deme_bench::printCase(j, sim);
    return 0;
}
