// MESH-FLOOR benchmark: a bed of spheres resting on a floor meshed as a fine grid of triangles
// (224 x 224 squares = 100,352 triangles by default), then the very same bed on an analytical floor
// plane, so the cost of the mesh shows. Prints one JSON line per case.
//   usage: mesh_floor [squares per side] [sphere layers] [warm-up steps] [timed steps] [mesh|plane|both]
//
// The box is 0.1 x 0.1 m (as CPU-BED), spheres of radius 1 mm (4.5 floor squares across a sphere's
// diameter), E = 1e8 Pa, nu = 0.3, CoR = 0.5, mu = 0.5, density 2600, dt = 5e-6 s. The spheres start
// as an HCP lattice whose lowest layer sits a quarter radius above the floor, fall, land and are timed
// after the warm-up. The side walls are frictionless so the floor carries the whole weight: the
// floor force over the weight, averaged over the timed steps, checks the mesh contacts (on a flat
// tessellated floor every sphere must feel exactly the plane's force).
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <deme/deme.h>

#include "BenchUtil.h"

using namespace deme;
using namespace deme_bench;

namespace {

constexpr float BOX = 0.1f;       // floor side, m
constexpr float RADIUS = 0.001f;  // sphere radius, m
constexpr double DENSITY = 2600, G = 9.81, DT = 5e-6;

struct Options {
    int squares = 224;
    int layers = 3;     // 8,232 spheres
    int warm = 5000;    // 0.025 s: landed, floor force within a few % of the weight
    int steps = 1000;
    std::string which = "both";
};

// A BOX x BOX floor in the plane z = 0 of its own frame, centred on the origin: n x n squares, each
// split along a diagonal into two triangles (the diagonal alternates, so no direction is favoured).
DEMMeshConnected makeFloor(int n, const std::shared_ptr<DEMMaterial>& mat) {
    std::vector<float3> v;
    v.reserve((size_t)(n + 1) * (n + 1));
    const float h = BOX / n;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) v.push_back(make_float3(i * h - 0.5f * BOX, j * h - 0.5f * BOX, 0.f));
    std::vector<int3> f;
    f.reserve((size_t)2 * n * n);
    auto id = [n](int i, int j) { return j * (n + 1) + i; };
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if ((i + j) % 2 == 0) {
                f.push_back(make_int3(a, b, c));
                f.push_back(make_int3(a, c, d));
            } else {
                f.push_back(make_int3(a, b, d));
                f.push_back(make_int3(b, c, d));
            }
        }
    return DEMMeshConnected(std::move(v), std::move(f), mat);
}

// One run: the same bed on a meshed floor (meshFloor) or an analytical plane. Prints its JSON line.
void run(const Options& o, bool meshFloor) {
    const double t0 = seconds();
    DEMSolver sim;
    sim.SetVerbosity("WARNING");
    auto mat = sim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}});
    auto matWall = sim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.0}, {"Crr", 0.0}});
    sim.SetMaterialPropertyPair("mu", mat, matWall, 0.0);  // frictionless side walls

    const float spacing = 2.01f * RADIUS;
    // HCP layer pitch is spacing * sqrt(2/3); the lattice spans `layers` layers.
    const float layerPitch = spacing * 0.8164966f;
    const float zLow = 1.25f * RADIUS;  // lowest centres: a quarter radius of free fall above the floor
    const float height = (o.layers - 1) * layerPitch;
    sim.InstructBoxDomainDimension({-0.01f, BOX + 0.01f}, {-0.01f, BOX + 0.01f}, {-0.01f, zLow + height + 0.02f});
    auto walls = sim.AddExternalObject();
    walls->AddPlane(make_float3(0, 0, 0), make_float3(1, 0, 0), matWall);
    walls->AddPlane(make_float3(BOX, 0, 0), make_float3(-1, 0, 0), matWall);
    walls->AddPlane(make_float3(0, 0, 0), make_float3(0, 1, 0), matWall);
    walls->AddPlane(make_float3(0, BOX, 0), make_float3(0, -1, 0), matWall);

    std::shared_ptr<DEMMeshConnected> floorMesh;
    std::shared_ptr<DEMExternObj> floorPlane;
    size_t triangles = 0;
    if (meshFloor) {
        floorMesh = sim.AddWavefrontMeshObject(makeFloor(o.squares, mat));
        floorMesh->SetInitPos(make_float3(0.5f * BOX, 0.5f * BOX, 0.f));
        triangles = floorMesh->GetNumTriangles();
    } else {
        floorPlane = sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    }

    const float inset = RADIUS * 1.01f;
    const std::vector<float3> pts =
        HCPSampler(spacing).SampleBox(make_float3(0.5f * BOX, 0.5f * BOX, zLow + 0.5f * height),
                                      make_float3(0.5f * BOX - inset, 0.5f * BOX - inset, 0.5f * height + 1e-6f));
    const float mSphere = (float)(DENSITY * 4.0 / 3.0 * PI * RADIUS * RADIUS * RADIUS);
    sim.AddClumps(sim.LoadSphereType(mSphere, RADIUS, mat), pts);
    sim.SetInitTimeStep(DT);
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-G));
    sim.Initialize();
    auto floorTracker = meshFloor ? sim.Track(floorMesh) : sim.Track(floorPlane);
    const double setup = seconds() - t0;

    const double m = DENSITY * 4.0 / 3.0 * PI * RADIUS * RADIUS * RADIUS;
    const double weight = (double)pts.size() * m * G;
    // DEME_BENCH_VERBOSE=1: the floor force and contacts every 500 warm-up steps (on stderr).
    const bool verbose = std::getenv("DEME_BENCH_VERBOSE") != nullptr;
    const double tw = seconds();
    for (int i = 0; i < o.warm; i++) {
        sim.DoStepDynamics();
        if (verbose && (i + 1) % 500 == 0)
            std::fprintf(stderr, "  warm-up step %d  t = %.4f s  floor/weight %.4f  contacts/sphere %.3f\n", i + 1,
                         sim.GetSimTime(), -floorTracker->ContactForce().z / weight, sim.GetAvgSphContacts());
    }
    const double warmWall = seconds() - tw;

    double floorSum = 0.0;
    const double t1 = seconds();
    for (int i = 0; i < o.steps; i++) {
        sim.DoStepDynamics();
        floorSum += -floorTracker->ContactForce().z;
    }
    const double wall = seconds() - t1;

    const double floorForce = floorSum / o.steps;
    JsonLine j;
    j.add("case", meshFloor ? "MESH-FLOOR" : "MESH-FLOOR-ANALYTICAL")
        .add("backend", "cpu")
        .add("device", cpuName() + " x " + std::to_string(std::thread::hardware_concurrency()) + " threads")
        .add("triangles", (double)triangles)
        .add("spheres", (double)sim.GetNumSpheres())
        .add("contacts_per_sphere", sim.GetAvgSphContacts())
        .add("warmup_steps", (double)o.warm)
        .add("warmup_s", warmWall)
        .add("steps", (double)o.steps)
        .add("wall_s", wall)
        .add("sphere_steps_per_s", (double)sim.GetNumSpheres() * o.steps / wall)
        .add("peak_mem_mib", peakMemoryMiB())
        .add("setup_s", setup)
        .add("floor_force_avg_N", floorForce)
        .add("weight_N", weight)
        .add("floor_over_weight", floorForce / weight);
    addRunSummary(j, sim.GetRunSummary());
    std::cout << j.str() << std::endl;
    if (std::getenv("DEME_BENCH_TIMING")) sim.ShowTimingStats();
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    if (argc > 1) o.squares = std::atoi(argv[1]);
    if (argc > 2) o.layers = std::atoi(argv[2]);
    if (argc > 3) o.warm = std::atoi(argv[3]);
    if (argc > 4) o.steps = std::atoi(argv[4]);
    if (argc > 5) o.which = argv[5];
    if (o.squares < 1 || o.layers < 1 || o.warm < 0 || o.steps < 1 ||
        (o.which != "both" && o.which != "mesh" && o.which != "plane")) {
        std::fprintf(stderr,
                     "usage: mesh_floor [squares per side] [sphere layers] [warm-up steps] [timed steps] "
                     "[mesh|plane|both]\n");
        return 2;
    }
    if (o.which != "plane") run(o, true);
    if (o.which != "mesh") run(o, false);
    return 0;
}
