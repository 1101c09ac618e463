// The state edits behind scenes that change while they run (runtime/SceneEdits.h), checked on the
// host state itself: every owner, geometry and contact row keeps its values (owner, geometry and
// contact wildcards tagged with the ids users see) through an insertion and a removal, the contact
// set stays sorted, and the user-id maps stay each other's inverse.
#include <gtest/gtest.h>

#include <memory>

#include <deme/Error.h>

#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "runtime/SceneEdits.h"
#include "state/OwnerTypeOf.h"

using namespace deme;

namespace {

struct Fixture {
    std::shared_ptr<DEMMaterial> mat = std::make_shared<DEMMaterial>(
        std::map<std::string, double>{{"E", 1e7}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}}, 0);
    std::shared_ptr<DEMClumpTemplate> pair = std::make_shared<DEMClumpTemplate>();
    ModelLayout layout;
    Fixture() {
        pair->mass = 2.f;
        pair->MOI = make_float3(1.f);
        pair->radii = {0.05f, 0.05f};
        pair->relPos = {make_float3(-0.05f, 0, 0), make_float3(0.05f, 0, 0)};
        pair->materials = {mat, mat};
        layout.ownerWildcards = {"ow"};
        layout.geometryWildcards = {"gw"};
        layout.contactWildcards = {"cw"};
    }
    Scene scene(const std::vector<float3>& pos, bool withPlane) const {
        Scene sc;
        sc.materials = {mat};
        sc.hasDomain = true;
        sc.domainLo = make_float3(-1.f);
        sc.domainSize = make_float3(2.f);
        sc.batches.push_back(std::make_shared<DEMClumpBatch>(
            std::vector<std::shared_ptr<DEMClumpTemplate>>(pos.size(), pair), pos));
        if (withPlane) {
            auto plane = std::make_shared<DEMExternObj>();
            plane->AddPlane(make_float3(0, 0, -0.5f), make_float3(0, 0, 1), mat);
            sc.externObjs.push_back(plane);
        }
        return sc;
    }
};

// Tags: owner wildcard 100 + user id, sphere wildcard 1000 + user sphere id, the plane's 5000.
// Contacts: every sphere with the plane, tagged 10000 + user sphere id.
// Owners' results (state/SimState.h: a running state holds them for an edit): travel 100 + user id.
void tag(SimState& s) {
    s.owners.makeResults();
    for (size_t o = 0; o < s.owners.size(); o++) s.wildcards.owner[0][o] = 100.f + s.ownerInternalToUser[o];
    for (size_t o = 0; o < s.owners.size(); o++) s.owners.travel[o] = 100.f + s.ownerInternalToUser[o];
    for (size_t i = 0; i < s.spheres.size(); i++) s.wildcards.geometry[0][i] = 1000.f + s.sphereInternalToUser[i];
    s.wildcards.geometry[0][s.analyticalIdBase()] = 5000.f;
    ContactArrays& c = s.contacts;
    for (bodyID_t i = 0; i < (bodyID_t)s.spheres.size(); i++) {
        c.geomA.push_back(i);
        c.geomB.push_back(s.analyticalIdBase());
        c.wildcards.push_back(10000.f + s.sphereInternalToUser[i]);
        c.persistent.push_back(0);
        c.meshState.push_back(0);
        c.force.push_back(make_float3(0.f));
    }
}

void expectConsistent(const SimState& s) {
    const bodyID_t R = SimState::REMOVED_ID;
    for (size_t u = 0; u < s.ownerUserToInternal.size(); u++) {
        const bodyID_t o = s.ownerUserToInternal[u];
        if (o == R) continue;
        EXPECT_EQ(s.ownerInternalToUser[o], u);
        EXPECT_EQ(s.wildcards.owner[0][o], 100.f + u) << "owner " << u;
        EXPECT_EQ(s.owners.travel[o], 100.f + u) << "owner " << u;
    }
    for (size_t u = 0; u < s.sphereUserToInternal.size(); u++) {
        const bodyID_t i = s.sphereUserToInternal[u];
        if (i == R) continue;
        EXPECT_EQ(s.sphereInternalToUser[i], u);
        EXPECT_EQ(s.wildcards.geometry[0][i], 1000.f + u) << "sphere " << u;
        EXPECT_LT(s.spheres.owner[i], s.numClumps);
        EXPECT_GE(i, s.ownerSphereStart[s.spheres.owner[i]]);
        EXPECT_LT(i, s.ownerSphereStart[s.spheres.owner[i] + 1]);
    }
    EXPECT_EQ(s.wildcards.geometry[0][s.analyticalIdBase()], 5000.f);
    EXPECT_EQ(s.analytical.owner[0], s.numClumps) << "the plane's owner follows the clumps";
    EXPECT_EQ(s.ownerInternalToUser[s.analytical.owner[0]], 3u) << "and keeps its user id";
    // Owner types follow from the owners' order (state/OwnerTypeOf.h): the plane (user id 3) is the
    // analytical one, every other live owner a clump.
    for (size_t u = 0; u < s.ownerUserToInternal.size(); u++) {
        const bodyID_t o = s.ownerUserToInternal[u];
        if (o == R) continue;
        EXPECT_EQ(ownerTypeOf(s, o), u == 3 ? OWNER_ANALYTICAL : OWNER_CLUMP) << "owner " << u;
    }
    const ContactArrays& c = s.contacts;
    for (size_t k = 0; k < c.size(); k++) {
        EXPECT_EQ(c.geomB[k], s.analyticalIdBase());
        if (c.geomA[k] < s.spheres.size()) EXPECT_EQ(c.wildcards[k], 10000.f + s.sphereInternalToUser[c.geomA[k]]);
        if (k) EXPECT_LT(contactKey(c.geomA[k - 1], c.geomB[k - 1]), contactKey(c.geomA[k], c.geomB[k]));
    }
}

}  // namespace

TEST(SceneEditsState, InsertionAndRemovalKeepEveryRowsValuesAndIds) {
    const Fixture f;
    SimState s = assembleScene(f.scene({make_float3(-0.5f, 0, 0), make_float3(0, 0, 0), make_float3(0.5f, 0, 0)}, true),
                               f.layout);
    ASSERT_EQ(s.numWildcards, 1u);
    tag(s);
    expectConsistent(s);

    // Two clumps in: user ids 4 and 5 (after the three clumps and the plane), spheres 6..9.
    const SimState part = assembleScene(f.scene({make_float3(0.2f, 0.5f, 0), make_float3(-0.2f, 0.5f, 0)}, false), f.layout);
    insertClumps(s, part);
    ASSERT_EQ(s.numClumps, 5u);
    ASSERT_EQ(s.ownerUserToInternal.size(), 6u);
    ASSERT_EQ(s.sphereUserToInternal.size(), 10u);
    for (bodyID_t u : {4u, 5u}) {
        EXPECT_EQ(s.owners.travel[s.ownerUserToInternal[u]], 0.f);  // (the part assembled has no results)
        s.owners.travel[s.ownerUserToInternal[u]] = 100.f + u;
        s.wildcards.owner[0][s.ownerUserToInternal[u]] = 100.f + u;  // tag the newcomers (they start at 0)
        EXPECT_LT(s.ownerUserToInternal[u], s.numClumps);
    }
    for (bodyID_t u = 6; u < 10; u++) {
        EXPECT_EQ(s.wildcards.geometry[0][s.sphereUserToInternal[u]], 0.f);
        s.wildcards.geometry[0][s.sphereUserToInternal[u]] = 1000.f + u;
    }
    EXPECT_EQ(s.contacts.size(), 6u);
    expectConsistent(s);

    // Clump 1 (spheres 2, 3) and clump 4 (spheres 6, 7) out.
    std::vector<uint8_t> remove(s.owners.size(), 0);
    remove[s.ownerUserToInternal[1]] = 1;
    remove[s.ownerUserToInternal[4]] = 1;
    const RemovedClumps r = removeClumps(s, remove);
    EXPECT_EQ(r.count, 2u);
    EXPECT_EQ(r.mass, 4.0);
    EXPECT_EQ(s.numRemovedClumps, 2u);
    EXPECT_EQ(s.numClumps, 3u);
    EXPECT_EQ(s.spheres.size(), 6u);
    EXPECT_EQ(s.ownerUserToInternal[1], SimState::REMOVED_ID);
    EXPECT_EQ(s.ownerUserToInternal[4], SimState::REMOVED_ID);
    for (bodyID_t u : {2u, 3u, 6u, 7u}) EXPECT_EQ(s.sphereUserToInternal[u], SimState::REMOVED_ID);
    EXPECT_EQ(s.contacts.size(), 4u) << "the removed spheres' contacts are freed";
    EXPECT_EQ(s.contacts.wildcards.size(), 4u);
    expectConsistent(s);
    EXPECT_THROW(liveOwner(s, 1, "test"), deme::Error);
    EXPECT_THROW(liveOwner(s, 6, "test"), deme::Error);
    EXPECT_EQ(liveOwner(s, 5, "test"), s.ownerUserToInternal[5]);
}
