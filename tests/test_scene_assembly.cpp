// Scene assembly at Initialize (api/SceneAssembly.cpp) fills the owners' and spheres' arrays in
// parallel, each clump its own rows: the state must be the one a single thread makes, array for
// array, and the first clump whose position does not fit must still be the one named.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>
#include <cstdint>

#include "BackendFixture.h"
#include "MeshBuilders.h"
#include "TestHelpers.h"
#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "parallel/Parallel.h"
#include "runtime/SceneEdits.h"
#include "runtime/SceneFingerprint.h"
#include "state/SphereIds.h"
#include "state/OwnerTypeOf.h"
#include "state/SphereLayoutChoice.h"

using namespace deme;
using namespace deme_test;

namespace {

std::shared_ptr<DEMClumpTemplate> clumpOf(size_t spheres, const std::shared_ptr<DEMMaterial>& mat) {
    auto t = std::make_shared<DEMClumpTemplate>();
    t->mass = 1.f;
    t->MOI = make_float3(1.f);
    for (size_t k = 0; k < spheres; k++) {
        t->radii.push_back(0.004f + 0.001f * (float)k);
        t->relPos.push_back(make_float3(0.005f * (float)k, 0.f, 0.f));
        t->materials.push_back(mat);
    }
    return t;
}

// A scene of one material in the domain [-1, 1]^3, without clumps yet.
Scene sceneWithOneMaterial() {
    Scene sc;
    sc.materials = {std::make_shared<DEMMaterial>(
        std::map<std::string, double>{{"E", 1e7}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}}, 0)};
    sc.hasDomain = true;
    sc.domainLo = make_float3(-1.f);
    sc.domainSize = make_float3(2.f);
    return sc;
}

// 6,000 clumps (over the parallel loops' threshold) of a one-sphere and a three-sphere template in
// random order and places, with per-clump velocities and families, in two batches. `outside`: two
// clumps (this one and the one 700 after it) at x = 0.95, past a domain that ends at x = 0.92 (as
// if it had been made smaller after AddClumps checked them).
Scene randomScene(size_t outside = SIZE_MAX) {
    Scene sc = sceneWithOneMaterial();
    const auto mat = sc.materials[0];
    const auto one = clumpOf(1, mat), three = clumpOf(3, mat);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> x(-0.9f, 0.9f);
    for (int batch = 0; batch < 2; batch++) {
        std::vector<std::shared_ptr<DEMClumpTemplate>> types;
        std::vector<float3> pos, vel;
        std::vector<unsigned int> fam;
        for (int i = 0; i < 3000; i++) {
            types.push_back(rng() % 3 ? one : three);
            pos.push_back(make_float3(x(rng), x(rng), x(rng)));
            const size_t u = 3000 * (size_t)batch + (size_t)i;
            if (outside != SIZE_MAX && (u == outside || u == outside + 700)) pos.back().x = 0.95f;
            vel.push_back(make_float3(x(rng), 0.f, 1.f));
            fam.push_back(rng() % 4);
        }
        auto b = std::make_shared<DEMClumpBatch>(types, pos);
        b->SetVel(vel);
        b->SetFamily(fam);
        sc.batches.push_back(b);
    }
    if (outside != SIZE_MAX) sc.domainSize.x = 1.92f;
    return sc;
}

template <class V>
void expectSameField(const V& a, const V& b, const char* what) {
    ASSERT_EQ(a.size(), b.size()) << what;
    EXPECT_TRUE(std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0) << what;
}

// Every owner field and every sphere field of `a` and `b` the same, array for array.
void expectSameOwnersAndSpheres(const SimState& a, const SimState& b, const char* what) {
    forEachOwnerField(a.owners, b.owners,
                      [what](const auto& x, const auto& y, FieldRole) { expectSameField(x, y, what); });
    forEachSphereField(a.spheres, b.spheres,
                       [what](const auto& x, const auto& y, FieldRole) { expectSameField(x, y, what); });
}

}  // namespace

TEST(SceneAssembly, ParallelAssemblyIsTheSerialOneArrayForArray) {
    const Scene sc = randomScene();
    const ModelLayout layout{};
    const int threads = cpuThreadCount();
    setCpuThreadCount(1);
    const SimState serial = assembleScene(sc, layout);
    setCpuThreadCount(std::max(2, threads));
    const SimState parallel = assembleScene(sc, layout);
    setCpuThreadCount(threads);
    ASSERT_EQ(serial.owners.size(), 6000u);
    EXPECT_GT(serial.spheres.size(), 6000u);
    expectSameOwnersAndSpheres(serial, parallel, "owner or sphere field");
    expectSameField(serial.ownerUserToInternal, parallel.ownerUserToInternal, "ownerUserToInternal");
    expectSameField(serial.ownerInternalToUser, parallel.ownerInternalToUser, "ownerInternalToUser");
    expectSameField(serial.sphereUserToInternal, parallel.sphereUserToInternal, "sphereUserToInternal");
    expectSameField(serial.sphereInternalToUser, parallel.sphereInternalToUser, "sphereInternalToUser");
    expectSameField(serial.ownerSphereStart, parallel.ownerSphereStart, "ownerSphereStart");
    // Neighbours in memory are neighbours in space: not the user order.
    size_t inUserOrder = 0;
    for (size_t k = 0; k < serial.ownerInternalToUser.size(); k++) inUserOrder += serial.ownerInternalToUser[k] == k;
    EXPECT_LT(inUserOrder, 100u);
}

TEST(SceneAssembly, TheFirstClumpOutsideTheDomainIsNamed) {
    const Scene sc = randomScene(4100);  // clumps 4100 and 4800 (the second batch's 1100th and 1800th)
    const std::string msg = demeErrorMessage([&] { assembleScene(sc, ModelLayout{}); });
    EXPECT_NE(msg.find("Initialize"), std::string::npos) << msg;
    EXPECT_NE(msg.find("clump 4100 at (0.95"), std::string::npos) << msg;
    EXPECT_NE(msg.find("outside the simulation domain"), std::string::npos) << msg;
}

// Where every clump is one sphere at its centre the assembly makes the spheres their owners at once
// (no sphere owners, offsets, id maps or first spheres: 24 B a sphere at a GPU run's host peak),
// the state the full assembly (DEME_FULL_SPHERE_LAYOUT=1) comes to once its layout is chosen: the
// same owners, radii and materials array for array, the same sphere ranges, owners and id maps as
// the layout's readers make them, and the same fingerprint (a checkpoint of one reads in the other).
TEST(SceneAssembly, OneSphereClumpsAreTheirOwnersFromTheStart) {
    Scene sc = sceneWithOneMaterial();
    const auto mat = sc.materials[0];
    auto small = clumpOf(1, mat), large = clumpOf(1, mat);
    large->radii[0] = 0.006f;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> x(-0.9f, 0.9f);
    for (int batch = 0; batch < 3; batch++) {
        std::vector<std::shared_ptr<DEMClumpTemplate>> types;
        std::vector<float3> pos;
        for (int i = 0; i < (batch == 1 ? 0 : 2500); i++) {  // (an empty batch between two)
            types.push_back(rng() % 2 ? small : large);
            pos.push_back(make_float3(x(rng), x(rng), x(rng)));
        }
        sc.batches.push_back(std::make_shared<DEMClumpBatch>(types, pos));
    }
    const ModelLayout layout{};
    const SimState compact = assembleScene(sc, layout);
    SimState full;
    {
        const ScopedEnvironmentVariable forced("DEME_FULL_SPHERE_LAYOUT", "1");
        full = assembleScene(sc, layout);
    }
    ASSERT_EQ(compact.owners.size(), 5000u);
    ASSERT_EQ(compact.spheres.size(), 5000u);
    EXPECT_TRUE(compact.spheresAreOwners);
    EXPECT_TRUE(compact.sphereIdsAreOwnerIds);
    EXPECT_FALSE(full.spheresAreOwners);
    EXPECT_TRUE(compact.spheres.owner.empty() && compact.spheres.relPos.empty() && compact.ownerSphereStart.empty());
    EXPECT_TRUE(compact.sphereInternalToUser.empty() && compact.sphereUserToInternal.empty());
    EXPECT_EQ(0u, fingerprintMismatch(sceneFingerprint(full, layout), sceneFingerprint(compact, layout)).size())
        << fingerprintMismatch(sceneFingerprint(full, layout), sceneFingerprint(compact, layout));
    forEachOwnerField(full.owners, compact.owners,
                      [](const auto& a, const auto& b, FieldRole) { expectSameField(a, b, "owner field"); });
    expectSameField(full.spheres.radius, compact.spheres.radius, "radius");
    expectSameField(full.spheres.material, compact.spheres.material, "material");
    expectSameField(full.ownerUserToInternal, compact.ownerUserToInternal, "ownerUserToInternal");
    expectSameField(full.ownerInternalToUser, compact.ownerInternalToUser, "ownerInternalToUser");
    std::vector<uint32_t> ranges;
    ownerSphereRanges(compact, ranges);
    expectSameField(full.ownerSphereStart, ranges, "ownerSphereStart");
    std::vector<bodyID_t> owners, toUser, toInternal;
    sphereOwners(compact, owners);
    expectSameField(full.spheres.owner, owners, "sphere owners");
    sphereIdMaps(compact, toUser, toInternal);
    expectSameField(full.sphereInternalToUser, toUser, "sphereInternalToUser");
    expectSameField(full.sphereUserToInternal, toInternal, "sphereUserToInternal");
    // Rows whose spheres are their owners merge into a running state (which holds its owners'
    // results, state/SimState.h) as their full arrays do.
    full.owners.makeResults();
    SimState intoCompact = full, intoFull = full;
    insertClumps(intoCompact, compact);
    insertClumps(intoFull, full);
    expectSameOwnersAndSpheres(intoFull, intoCompact, "merged owner or sphere field");
    expectSameField(intoFull.sphereUserToInternal, intoCompact.sphereUserToInternal, "merged sphereUserToInternal");
    expectSameField(intoFull.ownerSphereStart, intoCompact.ownerSphereStart, "merged ownerSphereStart");
    // A scene with a clump of two spheres is assembled in the full layout, as before.
    sc.batches.push_back(std::make_shared<DEMClumpBatch>(
        std::vector<std::shared_ptr<DEMClumpTemplate>>{clumpOf(2, mat)}, std::vector<float3>{make_float3(0.f)}));
    EXPECT_FALSE(assembleScene(sc, layout).spheresAreOwners);
}

// An owner's type is its place among the owners (state/OwnerTypeOf.h): the assembly puts the clumps
// first, then the external objects' owners, then the meshes, whatever order they were added in.
TEST(SceneAssembly, OwnerTypesFollowTheOwnersOrder) {
    Scene sc = sceneWithOneMaterial();
    const auto mat = sc.materials[0];
    auto mesh = std::make_shared<DEMMeshConnected>(boxMesh(make_float3(0.5f), make_float3(0.6f), mat));
    sc.meshes.push_back(mesh);
    for (int k = 0; k < 2; k++) {
        auto wall = std::make_shared<DEMExternObj>();
        wall->AddPlane(make_float3(0.f, 0.f, -0.9f + 0.1f * (float)k), make_float3(0.f, 0.f, 1.f), mat);
        sc.externObjs.push_back(wall);
    }
    sc.batches.push_back(std::make_shared<DEMClumpBatch>(
        std::vector<std::shared_ptr<DEMClumpTemplate>>{clumpOf(1, mat), clumpOf(3, mat), clumpOf(1, mat)},
        std::vector<float3>{make_float3(-0.5f), make_float3(0.f), make_float3(0.3f)}));
    const SimState s = assembleScene(sc, ModelLayout{});
    ASSERT_EQ(s.owners.size(), 6u);
    const uint8_t expected[] = {OWNER_CLUMP, OWNER_CLUMP, OWNER_CLUMP, OWNER_ANALYTICAL, OWNER_ANALYTICAL, OWNER_MESH};
    for (size_t o = 0; o < 6; o++) EXPECT_EQ(ownerTypeOf(s, o), expected[o]) << "owner " << o;
    EXPECT_EQ(s.analytical.owner[0], 3u);  // the walls' components name the owners typed analytical
    EXPECT_EQ(s.analytical.owner[1], 4u);
    EXPECT_EQ(s.triangles.owner[0], 5u);  // and the mesh's triangles the one typed mesh
}
