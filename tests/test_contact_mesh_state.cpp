// A contact set's mesh state (bit 0: a sphere-triangle contact counts this step, bit 1: it counted in
// the one before) matters for sphere-triangle pairs only, so the CPU's set keeps none in a scene
// without triangles (1 byte a pair: docs/memory.md) and carries it from set to set where there are
// triangles. History mapping alone, on the CPU: a plain test.
#include <gtest/gtest.h>

#include <vector>

#include "DetectedPairs.h"
#include "backend/cpu/HistoryMapping.h"

using namespace deme;
using namespace deme_test;

namespace {

// Four spheres, owners of themselves; `triangles` triangles after them (of owner 4) in the id space.
SimState spheresAndTriangles(size_t triangles) {
    SimState s;
    s.spheres.owner = {0, 1, 2, 3};
    s.owners.voxel.assign(triangles ? 5 : 4, 0);
    s.owners.family.assign(s.owners.voxel.size(), 0);
    s.triangles.owner.assign(triangles, 4);
    return s;
}

}  // namespace

TEST(ContactMeshState, KeptOnlyWhereTheSceneHasTriangles) {
    {
        SimState s = spheresAndTriangles(0);
        DetectedContacts fresh = detected({{0, 1}, {1, 2}, {2, 3}});
        installDetectedContacts(s, fresh, false);
        EXPECT_EQ(s.contacts.size(), 3u);
        EXPECT_TRUE(s.contacts.meshState.empty()) << "no triangles, no mesh state";
        DetectedContacts again = detected({{0, 1}, {2, 3}});
        installDetectedContacts(s, again, false);
        EXPECT_EQ(s.contacts.size(), 2u);
        EXPECT_TRUE(s.contacts.meshState.empty());
    }
    // Triangles 4 and 5 in the id space (after the four spheres): the sphere-triangle pairs' states
    // go to the next set where it has the pair; a new pair starts at 0.
    SimState s = spheresAndTriangles(2);
    DetectedContacts fresh = detected({{0, 1}, {0, 4}, {1, 5}});
    installDetectedContacts(s, fresh, false);
    ASSERT_EQ(s.contacts.meshState.size(), 3u);
    s.contacts.meshState = {0, 3, 1};  // (0,4) counted now and before, (1,5) now
    DetectedContacts next = detected({{0, 4}, {1, 2}, {2, 5}});
    installDetectedContacts(s, next, false);
    EXPECT_EQ(s.contacts.meshState, (std::vector<uint8_t>{3, 0, 0}));
}
