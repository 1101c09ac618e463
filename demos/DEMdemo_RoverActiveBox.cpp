// The paper's active box (§6.5.2), rover style: a wheel (a mesh with prescribed motion) drives
// over a bed of grains of which only the part around it moves. Every grain starts dormant (family
// 1: fixed, no contacts among dormant grains); a box that follows the wheel wakes the grains that
// enter it (family 0, free) and lets those it leaves behind fall dormant where they are, through two
// ChangeFamilyWhen conditions of position and time. The dormant grains still hold up the active
// ones, cost no integration, and are re-binned only when the set of dormant grains changes
// (docs/active-box.md). Prints per frame the wheel's position, the active grains and steps/s;
// writes sphere files (CSV) with each grain's family.
//   usage: DEMdemo_RoverActiveBox [output_dir] [--quick]
#include <deme/deme.h>

#include "DemoArgs.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

using namespace deme;
namespace fs = std::filesystem;

namespace {

// A closed cylinder about the y axis, centred at the origin: n segments, two rings and two caps,
// faces wound so that their normals point out.
DEMMeshConnected wheelMesh(float radius, float width, int n, const std::shared_ptr<DEMMaterial>& mat) {
    std::vector<float3> v;
    std::vector<int3> f;
    for (int side = 0; side < 2; side++)
        for (int i = 0; i < n; i++) {
            const float a = 2.f * (float)PI * (float)i / (float)n;
            v.push_back(make_float3(radius * std::cos(a), side ? 0.5f * width : -0.5f * width, radius * std::sin(a)));
        }
    const int c0 = (int)v.size(), c1 = c0 + 1;
    v.push_back(make_float3(0.f, -0.5f * width, 0.f));
    v.push_back(make_float3(0.f, 0.5f * width, 0.f));
    for (int i = 0; i < n; i++) {
        const int j = (i + 1) % n;
        f.push_back(make_int3(i, n + i, n + j));  // tread
        f.push_back(make_int3(i, n + j, j));
        f.push_back(make_int3(c0, i, j));  // caps
        f.push_back(make_int3(c1, n + j, n + i));
    }
    return DEMMeshConnected(v, f, mat);
}

}  // namespace

int main(int argc, char** argv) {
    const DemoArgs args = parseDemoArgs(argc, argv, "DemoOutput_RoverActiveBox");
    const bool quick = args.quick;
    fs::create_directories(args.outDir);

    DEMSolver sim;
    sim.SetVerbosity("WARNING");
    sim.SetOutputContent("FAMILY VEL");
    const double E = 1e7, nu = 0.3, density = 2500.0;
    auto mat = sim.LoadMaterial({{"E", E}, {"nu", nu}, {"CoR", 0.3}, {"mu", 0.5}, {"Crr", 0.01}});

    // The bed: a simple cubic lattice of touching grains (packed as it is, nothing to settle).
    const float r = 0.0025f;
    const int nx = quick ? 60 : 160, ny = quick ? 16 : 24, nz = quick ? 6 : 10;
    const float lx = 2 * r * nx, ly = 2 * r * ny, lz = 2 * r * nz;
    sim.InstructBoxDomainDimension({-0.05f, lx + 0.05f}, {-0.05f, ly + 0.05f}, {-0.05f, lz + 0.2f});
    sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    auto grain = sim.LoadSphereType((float)(density * 4.0 / 3.0 * PI * r * r * r), r, mat);
    std::vector<float3> xyz;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++) xyz.push_back(make_float3(r + 2 * r * i, r + 2 * r * j, r + 2 * r * k));
    auto bed = sim.AddClumps(grain, xyz);
    bed->SetFamily(1);  // dormant
    sim.SetFamilyFixed(1);
    sim.DisableContactBetweenFamilies(1, 1);

    // The wheel: r = 4 cm, 4 cm wide, across the bed's middle, starting 0.5 mm above it, driving in
    // +x at 0.2 m/s, rolling (w = v / R about y, in its own frame) and sinking gently into the bed
    // (vz = -0.02 exp(-4 t): 5 mm in all; a wheel placed into the lattice would blast it apart).
    const float R = 0.04f, v = 0.2f, x0 = 0.06f;
    auto wheel = sim.AddWavefrontMeshObject(wheelMesh(R, 0.04f, 48, mat));
    wheel->SetFamily(10);
    wheel->SetInitPos(make_float3(x0, 0.5f * ly, lz + R + 0.0005f));
    sim.SetFamilyPrescribedLinVel(10, std::to_string(v), "0", "-0.02 * exp(-4 * t)");
    sim.SetFamilyPrescribedAngVel(10, "0", std::to_string(v / R), "0");
    // The box reaches 1.5 wheel radii ahead and behind, so the wheel never meets a dormant grain:
    // its contacts with them are off, which lets detection keep the dormant grains cached.
    sim.DisableContactBetweenFamilies(10, 1);

    // The active box follows the wheel (its centre is x0 + v t): grains within 6 cm of it wake up;
    // active grains more than 8 cm from it fall dormant where they are (the 2 cm between the two
    // keeps a grain at the edge from waking and sleeping at every check).
    const std::string wheelX = "(" + std::to_string(x0) + " + " + std::to_string(v) + " * t)";
    sim.ChangeFamilyWhen(1, 0, "abs(X - " + wheelX + ") < 0.06");
    sim.ChangeFamilyWhen(0, 1, "abs(X - " + wheelX + ") > 0.08");

    const double dt = 2e-5;  // about 10 % of the grains' Rayleigh time (2.2e-4 s)
    sim.SetInitTimeStep(dt);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetErrorOutVelocity(20.f);
    sim.Initialize();
    auto tracker = sim.Track(bed);
    auto wheelTracker = sim.Track(wheel);

    const double frameTime = quick ? 0.01 : 0.05;
    const int frames = quick ? 3 : 30;
    std::printf("%zu grains (r = %.1f mm), wheel R = %.0f mm at %.2f m/s, dt = %.0e s\n", xyz.size(), 1e3 * r,
                1e3 * R, v, dt);
    size_t everActive = 0;
    std::vector<unsigned char> wasActive(xyz.size(), 0);
    for (int frame = 0; frame < frames; frame++) {
        const auto t0 = std::chrono::steady_clock::now();
        sim.DoDynamics(frameTime);
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const std::vector<unsigned int> fam = tracker->GetFamilies();
        size_t active = 0;
        for (size_t i = 0; i < fam.size(); i++) {
            active += fam[i] == 0u;
            if (fam[i] == 0u && !wasActive[i]) wasActive[i] = 1, everActive++;
        }
        std::printf("t = %.3f s, wheel x = %.3f m, active grains %zu of %zu, %.0f steps/s\n", sim.GetSimTime(),
                    wheelTracker->Pos().x, active, fam.size(), frameTime / dt / wall);
        char name[64];
        std::snprintf(name, sizeof name, "rover_%04d.csv", frame);
        sim.WriteSphereFile((args.outDir / name).string());
    }
    sim.FlushOutput();
    if (std::getenv("DEME_DEMO_TIMING")) sim.ShowTimingStats();
    // What the run must show: grains woke up along the wheel's path, and those far ahead never did.
    const std::vector<unsigned int> fam = tracker->GetFamilies();
    const double reach = x0 + v * sim.GetSimTime() + 0.06 + r;
    size_t wokeAhead = 0;
    for (size_t i = 0; i < fam.size(); i++)
        if (wasActive[i] && tracker->Pos(i).x > reach) wokeAhead++;
    std::printf("grains woken along the path: %zu; woken beyond the box's reach: %zu\n", everActive, wokeAhead);
    if (everActive == 0 || wokeAhead != 0) {
        std::fprintf(stderr, "DEMdemo_RoverActiveBox: the active box did not follow the wheel\n");
        return 1;
    }
    return 0;
}
