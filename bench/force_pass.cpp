// FORCE-PASS: one force pass over the CPU-BED bed's contact set (../shared/bench/bed60k.csv, detected
// once with a fixed margin), timed many times, with the built-in default model and with the same model
// written as a custom one (compiled at run time into the same loop), and the reduction of its loads
// onto the owners after each. The fastest pass is the figure least disturbed by other work on the
// machine. One JSON line per model.
//   usage: force_pass [bed60k.csv] [passes]
#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>

#include <deme/Error.h>

#include "BenchUtil.h"
#include "api/Scene.h"
#include "api/ForceModelSetup.h"
#include "api/SceneAssembly.h"
#include "parallel/Parallel.h"
#include "backend/cpu/CpuForceModel.h"
#include "backend/cpu/Integration.h"
#include "backend/cpu/StandaloneContactSet.h"
#include "state/SphereLayoutChoice.h"

using namespace deme;
using namespace deme_bench;

namespace {

// The CPU-BED scene as cpu_bed.cpp builds it through the API: walls, floor, 60,000 spheres.
Scene bedScene(const std::string& path) {
    Scene scene;
    auto mat = std::make_shared<DEMMaterial>(
        std::map<std::string, double>{{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}}, 0);
    scene.materials.push_back(mat);
    scene.hasDomain = true;
    scene.domainLo = make_float3(-0.01f, -0.01f, -0.01f);
    scene.domainSize = make_float3(0.12f, 0.12f, 0.21f);
    auto walls = std::make_shared<DEMExternObj>();
    walls->AddPlane(make_float3(0, 0, 0), make_float3(1, 0, 0), mat);
    walls->AddPlane(make_float3(0.1f, 0, 0), make_float3(-1, 0, 0), mat);
    walls->AddPlane(make_float3(0, 0, 0), make_float3(0, 1, 0), mat);
    walls->AddPlane(make_float3(0, 0.1f, 0), make_float3(0, -1, 0), mat);
    walls->AddPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    scene.externObjs.push_back(walls);
    std::ifstream f(path);
    if (!f) throw Error("force_pass: cannot open " + path);
    std::string line;
    std::getline(f, line);
    std::vector<float3> pos;
    float r = 0.f;
    while (std::getline(f, line)) {
        std::istringstream is(line);
        float x, y, z;
        char c;
        if (is >> x >> c >> y >> c >> z >> c >> r) pos.push_back(make_float3(x, y, z));
    }
    auto t = std::make_shared<DEMClumpTemplate>();
    t->mass = 2600.f * 4.18879f * r * r * r;
    t->MOI = make_float3(0.4f * t->mass * r * r);
    t->radii = {r};
    t->relPos = {make_float3(0.f)};
    t->materials = {mat};
    scene.templates.push_back(t);
    scene.batches.push_back(
        std::make_shared<DEMClumpBatch>(std::vector<std::shared_ptr<DEMClumpTemplate>>(pos.size(), t), pos));
    return scene;
}

std::shared_ptr<DEMForceModel> hertzMindlinAsSnippet() {
    std::ifstream body(DEME_SOURCE_DIR "/src/physics/models/HertzMindlin.inl");
    std::ostringstream code;
    code << "if (!(overlapDepth > 0.0)) {\n    delta_tan_x = delta_tan_y = delta_tan_z = delta_time = 0.f;\n"
            "    return;\n}\n"
         << body.rdbuf();
    auto m = std::make_shared<DEMForceModel>(DEMForceModel::Kind::CUSTOM, code.str());
    m->SetMustHaveMatProp({"E", "nu", "CoR", "mu", "Crr"});
    m->SetMustPairwiseMatProp({"CoR", "mu", "Crr"});
    m->SetPerContactWildcards({"delta_tan_x", "delta_tan_y", "delta_tan_z", "delta_time"});
    return m;
}

void timeModel(const Scene& scene, const DEMForceModel& model, const char* name, int passes) {
    const ModelLayout layout = resolveModelLayout(model, scene, "force_pass");
    SimState s = assembleScene(scene, layout);
    chooseSphereLayout(s);  // as Initialize does (DEME_FULL_SPHERE_LAYOUT=1: the full arrays)
    s.owners.makeResults();  // the loads the reduction writes (as the CPU backend makes them)
    const CpuForceModel active = loadCpuForceModel(layout, "force_pass");
    // The contact set of a detection with a 20 um margin (about a fifth of its pairs apart).
    detectAndInstallContacts(s, 2e-5);
    std::vector<double> t, tr;
    size_t real = 0;
    const IntegrationSubset all;
    for (int i = 0; i < passes; i++) {
        const double t0 = seconds();
        real = active.pass(s, 0.0, 5e-6, ForceStore::NONE).realContacts;
        const double t1 = seconds();
        reduceContactForces(s, all);
        t.push_back(t1 - t0);
        tr.push_back(seconds() - t1);
    }
    std::sort(t.begin(), t.end());
    std::sort(tr.begin(), tr.end());
    JsonLine j;
    j.add("case", "FORCE-PASS")
        .add("model", name)
        .add("device", cpuName() + " x " + std::to_string(cpuThreadCount()) + " threads")
        .add("pairs", (double)s.contacts.size())
        .add("touching", (double)real)
        .add("passes", (double)passes)
        .add("fastest_ms", t.front() * 1e3)
        .add("median_ms", t[t.size() / 2] * 1e3)
        .add("reduction_fastest_ms", tr.front() * 1e3)
        .add("reduction_median_ms", tr[tr.size() / 2] * 1e3);
    std::cout << j.str() << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string path = argc > 1 ? argv[1] : DEME_SHARED_BENCH_DIR "/bed60k.csv";
    const int passes = argc > 2 ? std::atoi(argv[2]) : 100;
    const Scene scene = bedScene(path);
    timeModel(scene, DEMForceModel(DEMForceModel::Kind::FRICTIONAL_HERTZIAN), "built-in", passes);
    timeModel(scene, *hertzMindlinAsSnippet(), "custom (Hertz-Mindlin as a snippet)", passes);
    return 0;
}
