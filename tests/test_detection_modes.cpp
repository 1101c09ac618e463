// Synchronous and asynchronous contact detection as the statistics report them, on every backend:
// synchronous detection runs on the dynamics side and never overlaps it, so no contact set arrives
// from an order and the dynamics side never waits; asynchronous detection on the same bed does
// deliver sets from orders (so the counter that stays at 0 above is live).
#include <gtest/gtest.h>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(DetectionModes);

namespace {

struct PourStats {
    unsigned long long asyncUpdates = 0;
    double waitShare = -1.0;
    size_t contacts = 0, spheres = 0;
};

// About 300 spheres (r = 2.5 mm) in an HCP block 1 mm above the floor of a box drop onto it and
// land within 0.05 s (2,500 steps): the contact sets change while detection runs.
void setUpPour(DEMSolver& sim, bool sync) {
    const float r = 0.0025f;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.5));
    sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.1f);
    sim.InstructBoxDomainBoundingBC("top_open", mat);
    const auto pts = HCPSampler(2.05f * r).SampleBox(make_float3(0, 0, -0.0385f), make_float3(0.02f, 0.02f, 0.008f));
    sim.AddClumps(sim.LoadSphereType((float)sphereMass(r, 2600), r, mat), pts);
    sim.SetInitTimeStep(2e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetSynchronousContactDetection(sync);
    sim.Initialize();
}

PourStats stats(const DEMSolver& sim) {
    PourStats s;
    s.asyncUpdates = sim.GetNumAsyncContactSetUpdates();
    s.waitShare = sim.GetDynamicsWaitShare();
    s.contacts = sim.GetNumContacts();
    s.spheres = sim.GetNumClumps();
    return s;
}

PourStats pour(bool sync) {
    DEMSolver sim;
    setUpPour(sim, sync);
    sim.DoDynamics(0.05);
    return stats(sim);
}

}  // namespace

DEME_BACKEND_TEST(DetectionModes, SynchronousDetectionSendsNoOrders) {
    const PourStats sync = pour(true);
    ASSERT_GE(sync.spheres, 250u);
    EXPECT_GT(sync.contacts, sync.spheres / 2);  // landed: grains touch the floor and each other
    EXPECT_EQ(sync.asyncUpdates, 0u);
    EXPECT_EQ(sync.waitShare, 0.0);
    const PourStats async = pour(false);
    EXPECT_GT(async.asyncUpdates, 0u);
    EXPECT_GT(async.contacts, async.spheres / 2);
}

// ClearThreadCollaborationStats starts the counters afresh (a settling phase left out of them): none
// just after, and the next call's own asynchronous sets after that.
DEME_BACKEND_TEST(DetectionModes, ClearedCountersDescribeTheRunAfter) {
    DEMSolver sim;
    setUpPour(sim, false);
    sim.DoDynamics(0.03);
    const unsigned long long before = sim.GetNumAsyncContactSetUpdates();
    ASSERT_GT(before, 0u);
    sim.ClearThreadCollaborationStats();
    EXPECT_EQ(sim.GetNumAsyncContactSetUpdates(), 0u);
    EXPECT_EQ(sim.GetDynamicsWaitShare(), 0.0);
    sim.DoDynamics(0.02);
    const PourStats after = stats(sim);
    EXPECT_GT(after.asyncUpdates, 0u);
    // The same 0.05 s without clearing: its lifetime total holds the first 0.03 s's sets too.
    DEMSolver twin;
    setUpPour(twin, false);
    twin.DoDynamics(0.03);
    twin.DoDynamics(0.02);
    EXPECT_LT(after.asyncUpdates, twin.GetNumAsyncContactSetUpdates());
    EXPECT_GE(after.waitShare, 0.0);
    EXPECT_LE(after.waitShare, 1.0);
}
