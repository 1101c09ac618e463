// ACTIVE-BOX: the paper's active box (§6.5.2) on a bed of n packed grains (default 10^6), stepped
// with the whole bed active, then with only its top layers (default 5 %) active and the rest
// dormant (docs/active-box.md): a fixed family whose contacts among itself are off.
//   active_box [cpu|cuda|auto] [grains] [active fraction] [timed steps (whole bed)] [timed steps (box)]
//              [auto|sync|async]
// The bed is a simple cubic lattice of touching spheres (r = 1 mm) on a floor, so it needs no
// settling: it is at rest from the first step, like a bed that settled. Prints one JSON line per
// case (steps/s over the timed steps, after 5 warm-up steps that include the first detection and
// the dormant registry's build) and a last line with the ratio.
#include <deme/deme.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "BenchUtil.h"

using namespace deme;

namespace {

struct CaseResult {
    double stepsPerSecond = 0.0;
};

CaseResult runCase(const std::string& backend, const std::string& mode, size_t grains, double activeFraction,
                   unsigned long steps, bool box) {
    const double r = 0.001, density = 2600.0, dt = 5e-6;
    const int side = (int)std::lround(std::cbrt((double)grains));
    const int layers = (int)((grains + (size_t)side * side - 1) / ((size_t)side * side));
    const int activeLayers = box ? std::max(1, (int)std::lround(activeFraction * layers)) : layers;
    DEMSolver sim;
    sim.SetVerbosity("WARNING");
    sim.SetBackend(backend);
    auto mat = sim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}});
    const float L = (float)(2 * r * side);
    sim.InstructBoxDomainDimension({-0.01f, L + 0.01f}, {-0.01f, L + 0.01f}, {-0.01f, (float)(2 * r * layers) + 0.05f});
    sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    auto grain = sim.LoadSphereType((float)(density * 4.0 / 3.0 * PI * r * r * r), (float)r, mat);
    std::vector<float3> xyz;
    std::vector<unsigned int> family;
    xyz.reserve(grains);
    for (int k = 0; k < layers; k++)
        for (int j = 0; j < side; j++)
            for (int i = 0; i < side && xyz.size() < grains; i++) {
                xyz.push_back(make_float3((float)(r + 2 * r * i), (float)(r + 2 * r * j), (float)(r + 2 * r * k)));
                family.push_back(k >= layers - activeLayers ? 0u : 1u);
            }
    auto bed = sim.AddClumps(grain, xyz);
    bed->SetFamily(family);
    sim.SetFamilyFixed(1);
    sim.DisableContactBetweenFamilies(1, 1);
    sim.SetInitTimeStep(dt);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    if (mode != "auto") sim.SetSynchronousContactDetection(mode == "sync");
    const double t0 = deme_bench::seconds();
    sim.Initialize();
    const double initSeconds = deme_bench::seconds() - t0;
    sim.DoDynamics(5 * dt);
    const double t1 = deme_bench::seconds();
    sim.DoDynamics((double)steps * dt);
    const double wall = deme_bench::seconds() - t1;
    size_t active = 0;
    for (unsigned int f : family) active += f == 0u;

    deme_bench::JsonLine j;
    j.add("case", box ? "ACTIVE-BOX active box" : "ACTIVE-BOX whole bed")
        .add("backend", sim.GetBackend())
        .add("device", sim.GetBackend() == "cpu" ? deme_bench::cpuName() : "GPU")
        .add("spheres", (double)sim.GetNumSpheres())
        .add("active_spheres", (double)active)
        .add("contacts_total", (double)sim.GetNumContacts())
        .add("steps", (double)steps)
        .add("wall_s", wall)
        .add("steps_per_s", (double)steps / wall)
        .add("update_freq", (double)sim.GetUpdateFreq())
        .add("detection", sim.UsesAsyncContactDetection() ? "async" : "sync")
        .add("initialize_s", initSeconds)
        .add("peak_host_mem_mib", deme_bench::peakMemoryMiB());
    deme_bench::printCase(j, sim);
    return CaseResult{(double)steps / wall};
}

}  // namespace

int main(int argc, char** argv) {
    const std::string backend = argc > 1 ? argv[1] : "cpu";
    const size_t grains = argc > 2 ? (size_t)std::strtoull(argv[2], nullptr, 10) : 1000000;
    const double fraction = argc > 3 ? std::atof(argv[3]) : 0.05;
    const unsigned long wholeSteps = argc > 4 ? std::strtoul(argv[4], nullptr, 10) : 80;
    const unsigned long boxSteps = argc > 5 ? std::strtoul(argv[5], nullptr, 10) : 400;
    const std::string mode = argc > 6 ? argv[6] : "auto";
    if ((backend != "cpu" && backend != "cuda" && backend != "auto") ||
        (mode != "auto" && mode != "sync" && mode != "async")) {
        std::fprintf(stderr, "usage: %s [cpu|cuda|auto] [grains] [active fraction] [steps] [box steps] [auto|sync|async]\n",
                     argv[0]);
        return 2;
    }
    const CaseResult whole = runCase(backend, mode, grains, fraction, wholeSteps, false);
    const CaseResult box = runCase(backend, mode, grains, fraction, boxSteps, true);
    deme_bench::JsonLine j;
    j.add("case", "ACTIVE-BOX ratio").add("backend", backend).add("speedup", box.stepsPerSecond / whole.stepsPerSecond);
    std::printf("%s\n", j.str().c_str());
    return 0;
}
