// A flat-bottomed hopper discharges through a square orifice (demos/HopperGeometry.h). Grains that
// fall through it leave the domain below and are removed (SetDomainExitPolicy("remove")); the mass
// removed per frame is the discharge's mass flow rate, printed frame by frame with its mean over
// the run. Half way, the hopper is topped up with a new layer of grains, added during the run
// (AddClumps + UpdateClumps). Writes sphere files (CSV) into the output folder.
//   usage: DEMdemo_HopperDischarge [output_dir] [--quick]
#include <deme/deme.h>

#include "DemoArgs.h"
#include "HopperGeometry.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace deme;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
    const DemoArgs args = parseDemoArgs(argc, argv, "DemoOutput_HopperDischarge");
    fs::create_directories(args.outDir);

    DEMSolver DEMSim;
    DEMSim.SetVerbosity("INFO");
    HopperSpec spec;
    if (!args.quick) {  // ~1,000 grains; --quick keeps the 100 of the test
        spec.nx = spec.ny = 10;
        spec.nz = 10;
        spec.halfWidth = 0.17f;
        spec.orificeHalf = 0.06f;  // 7.5 grain diameters: no arch holds
        spec.spacing = 0.0325f;
        spec.domainTop = 0.6f;
    }
    const Hopper hopper = buildHopper(DEMSim, spec);
    DEMSim.SetInitTimeStep(2e-5);
    DEMSim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    DEMSim.SetDomainExitPolicy("remove");
    DEMSim.Initialize();
    auto mass = DEMSim.CreateInspector("clump_mass");
    const double initialMass = mass->GetValue();

    const double frameTime = 0.05;
    const int frames = args.quick ? 6 : 40;
    const int topUpFrame = frames / 2;
    std::printf("%8s %8s %12s %14s\n", "t (s)", "grains", "removed (kg)", "flow (kg/s)");
    double lastRemoved = 0.0;
    for (int f = 1; f <= frames; f++) {
        if (f == topUpFrame) {
            // A new layer above the remaining grains: its ids follow all earlier ones.
            std::vector<float3> layer;
            for (int j = 0; j < spec.ny; j++)
                for (int i = 0; i < spec.nx; i++)
                    layer.push_back(make_float3((i - 0.5f * (spec.nx - 1)) * spec.spacing,
                                                (j - 0.5f * (spec.ny - 1)) * spec.spacing, spec.domainTop - 0.05f));
            auto grain = hopper.grains->GetTypes()[0];
            auto batch = DEMSim.AddClumps(grain, layer);
            DEMSim.UpdateClumps();
            std::printf("t = %.2f s: topped up with %zu grains (ids from %zu)\n", DEMSim.GetSimTime(),
                        batch->GetNumClumps(), batch->GetOwnerOffset());
        }
        DEMSim.DoDynamics(frameTime);
        const double removed = DEMSim.GetRemovedMass();
        std::printf("%8.3f %8zu %12.5f %14.5f\n", DEMSim.GetSimTime(), DEMSim.GetNumClumps(), removed,
                    (removed - lastRemoved) / frameTime);
        lastRemoved = removed;
        if (f % 2 == 0 || args.quick)
            DEMSim.WriteSphereFile((args.outDir / ("hopper_" + std::to_string(f) + ".csv")).string());
    }
    DEMSim.FlushOutput();
    const double t = DEMSim.GetSimTime();
    std::printf("discharged %zu grains, %.5f kg in %.2f s: mean mass flow rate %.5f kg/s\n",
                DEMSim.GetNumRemovedClumps(), DEMSim.GetRemovedMass(), t, DEMSim.GetRemovedMass() / t);
    // The bookkeeping: every grain is either still in the hopper or counted as removed.
    const double added = mass->GetValue() + DEMSim.GetRemovedMass() - initialMass;
    std::printf("mass in hopper %.5f kg + removed %.5f kg = initial %.5f kg + added %.5f kg\n", mass->GetValue(),
                DEMSim.GetRemovedMass(), initialMass, added);
    return DEMSim.GetNumRemovedClumps() > 0 ? 0 : 1;
}
