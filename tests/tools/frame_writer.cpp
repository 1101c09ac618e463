// Writes sphere frames to one path, over and over, for the test that kills a writer midway
// (test_output_failures.cpp): prints "writing <k> <time>" before frame k is handed to the writer and
// "written <k> <time>" once it is in place.
//   frame_writer <path.vtu> <spheres>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <deme/deme.h>

using namespace deme;

int main(int argc, char** argv) {
    if (argc < 3) return 2;
    const std::string path = argv[1];
    const int n = std::atoi(argv[2]);
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    sim.SetProgressReport(false);
    sim.SetBackend("cpu");
    sim.SetOutputFormat("VTU");
    // base64 and zlib: the slowest encoding, so that a kill most likely lands inside a write.
    sim.SetVTUEncoding("base64");
    sim.SetVTUCompression("zlib");
    sim.SetOutputContent("ABSV VEL OWNER");
    auto mat = sim.LoadMaterial({{"E", 1e7}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}});
    sim.InstructBoxDomainDimension(10, 10, 10);
    std::vector<float3> pos;
    const int side = (int)std::ceil(std::cbrt((double)n));
    for (int i = 0; i < n; i++)
        pos.push_back(make_float3(0.03f * (i % side) - 4.f, 0.03f * (i / side % side) - 4.f, 0.03f * (i / side / side) - 4.f));
    auto grains = sim.AddClumps(sim.LoadSphereType(1e-4f, 0.01f, mat), pos);
    grains->SetVel(make_float3(0.1f, 0.f, 0.f));
    sim.SetInitTimeStep(1e-4);
    sim.Initialize();
    for (int k = 0;; k++) {
        sim.DoStepDynamics();
        std::printf("writing %d %.17g\n", k, sim.GetSimTime());
        std::fflush(stdout);
        sim.WriteSphereFile(path);
        sim.FlushOutput();
        std::printf("written %d %.17g\n", k, sim.GetSimTime());
        std::fflush(stdout);
    }
}
