// Sphere ids shared with the owners' (state/SphereIds.h): a scene of one-sphere clumps added before
// any other owner keeps no sphere id maps, and every id reads as the maps gave it; an edit owns the
// maps while it runs and shares them again where the ids still agree (an insertion after a plane
// does not: the new clumps' owner ids follow the plane's, their sphere ids the spheres').
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "BackendFixture.h"
#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "runtime/SceneEdits.h"
#include "state/SphereIds.h"

using namespace deme;
using namespace deme_test;

namespace {

struct Ids {
    std::vector<bodyID_t> userOf, internalOf;
};

Ids idsOf(const SimState& s) {
    Ids ids;
    for (size_t i = 0; i < s.spheres.size(); i++) ids.userOf.push_back(sphereUserId(s, i));
    for (size_t u = 0; u < userSphereCount(s); u++) ids.internalOf.push_back(sphereInternalId(s, u));
    return ids;
}

Scene oneSphereClumps(const std::vector<float3>& pos, bool planeAfter) {
    auto mat = std::make_shared<DEMMaterial>(
        std::map<std::string, double>{{"E", 1e7}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}}, 0);
    auto ball = std::make_shared<DEMClumpTemplate>();
    ball->mass = 1.f;
    ball->MOI = make_float3(1.f);
    ball->radii = {0.05f};
    ball->relPos = {make_float3(0.f)};
    ball->materials = {mat};
    Scene sc;
    sc.materials = {mat};
    sc.hasDomain = true;
    sc.domainLo = make_float3(-1.f);
    sc.domainSize = make_float3(2.f);
    sc.batches.push_back(
        std::make_shared<DEMClumpBatch>(std::vector<std::shared_ptr<DEMClumpTemplate>>(pos.size(), ball), pos));
    if (planeAfter) {
        auto plane = std::make_shared<DEMExternObj>();
        plane->AddPlane(make_float3(0, 0, -0.5f), make_float3(0, 0, 1), mat);
        sc.externObjs.push_back(plane);
    }
    return sc;
}

// Every sphere's user id and back: each other's inverse over the live ids.
void expectInverse(const SimState& s) {
    for (size_t i = 0; i < s.spheres.size(); i++) EXPECT_EQ(sphereInternalId(s, sphereUserId(s, i)), i);
}

}  // namespace

TEST(SphereIds, SharedWithTheOwnersWhereTheyAgreeAndReadTheSame) {
    const std::vector<float3> pos = {make_float3(0.5f, 0, 0), make_float3(-0.5f, 0, 0), make_float3(0, 0.5f, 0),
                                     make_float3(0, -0.5f, 0)};
    const ScopedEnvironmentVariable shared("DEME_FULL_SPHERE_LAYOUT", "0");
    const ModelLayout layout;
    for (bool planeAfter : {true, false}) {
        // Assembled with the spheres' own arrays (as UpdateClumps' rows are; Initialize's assembly
        // shares them at once, test SceneAssembly.OneSphereClumpsAreTheirOwnersFromTheStart).
        SimState s = assembleScene(oneSphereClumps(pos, planeAfter), layout, false);
        s.owners.makeResults();  // (as a running state holds them for an edit: state/SimState.h)
        ASSERT_FALSE(s.sphereIdsAreOwnerIds);
        const Ids before = idsOf(s);
        shareSphereIdsWithOwners(s);
        EXPECT_TRUE(s.sphereIdsAreOwnerIds);
        EXPECT_TRUE(s.sphereInternalToUser.empty() && s.sphereUserToInternal.empty());  // no memory either
        EXPECT_EQ(s.sphereInternalToUser.capacity() + s.sphereUserToInternal.capacity(), 0u);
        const Ids shared = idsOf(s);
        EXPECT_EQ(shared.userOf, before.userOf);
        EXPECT_EQ(shared.internalOf, before.internalOf);

        // Two more clumps: their sphere ids are 4 and 5; their owner ids 4 and 5 only without the
        // plane (which took owner id 4 first).
        insertClumps(
            s, assembleScene(oneSphereClumps({make_float3(0.3f, 0.3f, 0), make_float3(-0.3f, -0.3f, 0)}, false), layout,
                             false));
        EXPECT_EQ(s.sphereIdsAreOwnerIds, !planeAfter);
        ASSERT_EQ(userSphereCount(s), 6u);
        expectInverse(s);
        for (bodyID_t u : {4u, 5u}) EXPECT_LT(sphereInternalId(s, u), s.spheres.size());

        // One of the first clumps and one of the new ones out: their ids stay issued, as removed.
        std::vector<uint8_t> remove(s.owners.size(), 0);
        remove[sphereInternalId(s, 1)] = 1;
        remove[sphereInternalId(s, 5)] = 1;
        removeClumps(s, remove);
        EXPECT_EQ(s.sphereIdsAreOwnerIds, !planeAfter);
        ASSERT_EQ(userSphereCount(s), 6u);
        EXPECT_EQ(sphereInternalId(s, 1), SimState::REMOVED_ID);
        EXPECT_EQ(sphereInternalId(s, 5), SimState::REMOVED_ID);
        expectInverse(s);

        // The maps made again from the owners' are the ids read through them.
        const Ids after = idsOf(s);
        ownSphereIds(s);
        EXPECT_FALSE(s.sphereIdsAreOwnerIds);
        EXPECT_EQ(s.sphereInternalToUser, after.userOf);
        EXPECT_EQ(s.sphereUserToInternal, after.internalOf);
    }
}
