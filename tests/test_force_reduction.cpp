// The CPU's force reduction: A's owner takes its loads in the force pass itself (each thread owns
// whole runs of owners' contacts), B's owner in the reduction from the per-contact force and torque.
// Checked on a compressed block of three-sphere clumps between walls, with thousands of pairs so that
// the pass splits them among threads and chunks: every owner's sums obey Newton's third law and the
// balance of angular momentum (a pair's loads cancel, whatever owner takes them), and they are the
// same bit for bit for 1, 2 and 3 threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include "api/ForceModelSetup.h"
#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "backend/cpu/CpuForceModel.h"
#include "backend/cpu/Integration.h"
#include "backend/cpu/StandaloneContactSet.h"
#include "parallel/Parallel.h"

using namespace deme;

namespace {

const float kRadius = 1e-3f;

// Three-sphere clumps on a grid closer than their size, turned differently, between two walls:
// most pairs overlap, and each clump's run of contacts as A mixes sphere and wall pairs.
Scene compressedBlock() {
    Scene scene;
    auto mat = std::make_shared<DEMMaterial>(
        std::map<std::string, double>{{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.05}}, 0);
    scene.materials.push_back(mat);
    scene.hasDomain = true;
    scene.domainLo = make_float3(-0.01f);
    scene.domainSize = make_float3(0.06f);
    auto walls = std::make_shared<DEMExternObj>();
    walls->AddPlane(make_float3(0, 0, 0.0005f), make_float3(0, 0, 1), mat);
    walls->AddPlane(make_float3(0.0005f, 0, 0), make_float3(1, 0, 0), mat);
    scene.externObjs.push_back(walls);
    auto t = std::make_shared<DEMClumpTemplate>();
    t->mass = 1e-5f;
    t->MOI = make_float3(1e-11f, 1.2e-11f, 1.4e-11f);
    t->radii = {kRadius, 0.8f * kRadius, 0.9f * kRadius};
    t->relPos = {make_float3(0.f), make_float3(1.2f * kRadius, 0, 0), make_float3(0, 1.1f * kRadius, 0)};
    t->materials = {mat, mat, mat};
    scene.templates.push_back(t);
    std::vector<float3> pos;
    std::vector<float4> q;
    const float gap = 2.1f * kRadius;
    for (int k = 0; k < 12; k++)
        for (int j = 0; j < 12; j++)
            for (int i = 0; i < 12; i++) {
                pos.push_back(make_float3(gap * (i + 0.5f), gap * (j + 0.5f), gap * (k + 0.5f)));
                const float a = 0.37f * (float)(i + 3 * j + 7 * k);
                q.push_back(make_float4(0.f, 0.f, std::sin(a), std::cos(a)));
            }
    auto batch =
        std::make_shared<DEMClumpBatch>(std::vector<std::shared_ptr<DEMClumpTemplate>>(pos.size(), t), pos);
    batch->SetOriQ(q);
    std::vector<float3> v;
    for (size_t n = 0; n < pos.size(); n++) v.push_back(make_float3(0.01f * (float)(n % 7), -0.02f * (float)(n % 5), 0.f));
    batch->SetVel(v);
    scene.batches.push_back(batch);
    return scene;
}

struct Loads {
    std::vector<float3> force, torque;
};

// The block's contact set, one force pass (the built-in Hertz-Mindlin model) and the reduction with
// `threads` threads; every owner's contact force and torque.
Loads passAndReduce(const Scene& scene, int threads, SimState* out = nullptr) {
    const int before = cpuThreadCount();
    setCpuThreadCount(threads);
    const ModelLayout layout =
        resolveModelLayout(DEMForceModel(DEMForceModel::Kind::FRICTIONAL_HERTZIAN), scene, "test");
    SimState s = assembleScene(scene, layout);
    const CpuForceModel model = loadCpuForceModel(layout, "test");
    detectAndInstallContacts(s, 2e-4);
    model.pass(s, 0.0, 1e-6);
    IntegrationSubset all;
    reduceContactForces(s, all);
    setCpuThreadCount(before);
    if (out) *out = s;
    return Loads{s.owners.contactForce, s.owners.contactTorque};
}

double3 toD(const float3& v) { return make_double3(v.x, v.y, v.z); }

}  // namespace

TEST(ForceReduction, OwnersSumsCancelAndDoNotDependOnTheThreadCount) {
    const Scene scene = compressedBlock();
    SimState s;
    const Loads one = passAndReduce(scene, 1, &s);
    // Large enough that the pass splits its contacts among threads and each thread's share among
    // several chunks (parallel/Parallel.h, backend/cpu/ForcePassLoop.h).
    ASSERT_GT(s.contacts.size(), 8 * PARALLEL_MIN_ITEMS);
    size_t wallPairs = 0;
    for (uint8_t t : s.contacts.type) wallPairs += t == SPHERE_ANALYTICAL;
    ASSERT_GT(wallPairs, 100u);

    // Newton's third law and the balance of angular momentum over all owners (the walls included):
    // every pair's force and moments cancel, so the sums are zero to the float rounding of the
    // loads (scale: the largest owner load times the number of contacts' rounding).
    double3 F = make_double3(0, 0, 0), L = make_double3(0, 0, 0);
    double fScale = 0.0, lScale = 0.0;
    for (size_t o = 0; o < s.owners.size(); o++) {
        const double3 f = toD(one.force[o]), x = s.cache.ownerPos[o];
        const double3 l = toD(one.torque[o]) + cross(x, f);
        F = F + f;
        L = L + l;
        fScale = std::max(fScale, length(f));
        lScale = std::max(lScale, length(l));
    }
    ASSERT_GT(fScale, 0.0);
    const double rounding = 1e-6 * std::sqrt((double)s.contacts.size());
    EXPECT_LT(length(F), rounding * fScale) << "sum of forces " << F.x << " " << F.y << " " << F.z;
    EXPECT_LT(length(L), rounding * lScale) << "sum of moments " << L.x << " " << L.y << " " << L.z;

    // The same sums, bit for bit, whatever the number of threads.
    for (int threads : {2, 3}) {
        const Loads many = passAndReduce(scene, threads);
        ASSERT_EQ(many.force.size(), one.force.size());
        for (size_t o = 0; o < one.force.size(); o++) {
            ASSERT_EQ(std::memcmp(&many.force[o], &one.force[o], sizeof(float3)), 0) << "owner " << o;
            ASSERT_EQ(std::memcmp(&many.torque[o], &one.torque[o], sizeof(float3)), 0) << "owner " << o;
        }
    }
}
