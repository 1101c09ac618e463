// Tracker loads (DEMTracker::AddAcc, AddAngAcc): held only from the first load to the end of the
// call that applies them (state/StateFields.h), on every backend; they act on their own owners
// only, stay with them through scene edits and travel in a checkpoint written before the call.
#include <gtest/gtest.h>

#include <cmath>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(TrackerLoads);

namespace {

constexpr float RADIUS = 0.05f;

// Balls far apart in a box without gravity, and a plane (an analytical owner after the clumps, so
// that clumps added later are inserted before it).
struct LoadScene {
    DEMSolver sim;
    std::shared_ptr<DEMMaterial> mat;
    std::shared_ptr<DEMClumpTemplate> ball;
    std::shared_ptr<DEMClumpBatch> a, b;
    LoadScene() {
        sim.SetVerbosity("QUIET");
        mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.3));
        sim.InstructBoxDomainDimension(2, 2, 2);
        sim.AddBCPlane(make_float3(0, 0, -0.9f), make_float3(0, 0, 1), mat);
        ball = sim.LoadSphereType(1.f, RADIUS, mat);
        a = sim.AddClumps(ball, {make_float3(-0.5f, 0, 0)});
        b = sim.AddClumps(ball, {make_float3(0.5f, 0, 0)});
        sim.SetGravitationalAcceleration(make_float3(0.f));
        sim.SetInitTimeStep(1e-4);
    }
    size_t hostOwnerBytes() const { return sim.GetMemoryStats().host(MemoryGroup::OWNER_STATE); }
    size_t deviceOwnerBytes() const { return sim.GetMemoryStats().device(MemoryGroup::OWNER_STATE); }
};

}  // namespace

// The two arrays (24 bytes per owner) exist on the host from the first load to the end of the call
// that applies it; the GPU keeps its copy's storage once made (a run adding loads call after call
// allocates it once). The load acts during that call only, on its own owner only.
DEME_BACKEND_TEST(TrackerLoads, HeldOnlyWhileACallHasSome) {
    LoadScene s;
    s.sim.Initialize();
    auto ta = s.sim.Track(s.a), tb = s.sim.Track(s.b);
    s.sim.DoDynamics(0.01);
    const size_t owners = 3;  // two balls and the plane
    const size_t host0 = s.hostOwnerBytes(), device0 = s.deviceOwnerBytes();
    ta->AddAcc(make_float3(0, 2.f, 0));
    ta->AddAngAcc(make_float3(0, 0, 4.f));
    EXPECT_EQ(s.hostOwnerBytes(), host0 + owners * 2 * sizeof(float3));
    s.sim.DoDynamics(0.1);
    EXPECT_EQ(s.hostOwnerBytes(), host0) << "released when the call that applied them ends";
    if (onGpu()) {
        const size_t grown = s.deviceOwnerBytes() - device0;
        EXPECT_GE(grown, owners * 2 * sizeof(float3));
        EXPECT_LE(grown, owners * 2 * sizeof(float3) + 2 * 4096) << "the two arrays, allocation granularity aside";
    } else {
        EXPECT_EQ(s.deviceOwnerBytes(), device0);
    }
    // v = a t and w = alpha t over the call (first-order integration: to float rounding).
    EXPECT_NEAR(ta->Vel().y, 0.2, 1e-5);
    EXPECT_NEAR(ta->AngVelLocal().z, 0.4, 1e-5);
    EXPECT_EQ(tb->Vel().y, 0.f);
    EXPECT_EQ(tb->AngVelLocal().z, 0.f);
    // The next call has none: the velocities stay, and the GPU's storage is not made again.
    const size_t device1 = s.deviceOwnerBytes();
    s.sim.DoDynamics(0.1);
    EXPECT_NEAR(ta->Vel().y, 0.2, 1e-5);
    EXPECT_NEAR(ta->AngVelLocal().z, 0.4, 1e-5);
    ta->AddAcc(make_float3(0, -2.f, 0));
    s.sim.DoDynamics(0.1);
    EXPECT_NEAR(ta->Vel().y, 0.0, 1e-5);
    EXPECT_EQ(s.deviceOwnerBytes(), device1);
    EXPECT_EQ(s.hostOwnerBytes(), host0);
}

// Loads added before UpdateClumps (which inserts the new clumps before the plane) and before a
// removal (which renumbers the owners after the removed one) stay with their own owners.
DEME_BACKEND_TEST(TrackerLoads, StayWithTheirOwnersThroughSceneEdits) {
    LoadScene s;
    s.a->SetFamily(7);
    s.sim.Initialize();
    auto ta = s.sim.Track(s.a), tb = s.sim.Track(s.b);
    ta->AddAcc(make_float3(0, 2.f, 0));
    auto added = s.sim.AddClumps(s.ball, {make_float3(0, 0.5f, 0), make_float3(0, -0.5f, 0)});
    auto tc = s.sim.Track(added);
    s.sim.UpdateClumps();
    tc->AddAcc(make_float3(0, 0, 3.f), 1);
    s.sim.DoDynamics(0.1);
    EXPECT_NEAR(ta->Vel().y, 0.2, 1e-5);
    EXPECT_EQ(tb->Vel().y, 0.f);
    EXPECT_EQ(tc->Vel(0).z, 0.f);
    EXPECT_NEAR(tc->Vel(1).z, 0.3, 1e-5);

    // a (family 7) goes; b's load, added before the removal, stays b's although b's id changes.
    tb->AddAcc(make_float3(0, 0, -1.f));
    EXPECT_EQ(s.sim.RemoveClumpsInFamily(7), 1u);
    s.sim.DoDynamics(0.1);
    EXPECT_NEAR(tb->Vel().z, -0.1, 1e-5);
    EXPECT_EQ(tb->Vel().y, 0.f);
    EXPECT_NEAR(tc->Vel(1).z, 0.3, 1e-5);
    EXPECT_EQ(tc->Vel(0).z, 0.f);
}

// A checkpoint written while loads are pending carries them: the restarted call applies them, bit
// for bit as the call that wrote it.
DEME_BACKEND_TEST(TrackerLoads, PendingLoadsTravelInACheckpoint) {
    const std::string path = (scratchDir() / "loads.ckpt").string();
    float3 v, w;
    {
        LoadScene s;
        s.sim.Initialize();
        s.sim.DoDynamics(0.01);
        auto ta = s.sim.Track(s.a);
        ta->AddAcc(make_float3(0.5f, 2.f, 0));
        ta->AddAngAcc(make_float3(0, 1.f, 4.f));
        s.sim.WriteCheckpoint(path);
        s.sim.DoDynamics(0.1);
        v = ta->Vel();
        w = ta->AngVelLocal();
        EXPECT_NEAR(v.y, 0.2, 1e-5);
    }
    LoadScene s;
    s.sim.Initialize();
    s.sim.ReadCheckpoint(path);
    auto ta = s.sim.Track(s.a);
    s.sim.DoDynamics(0.1);
    EXPECT_EQ(ta->Vel().x, v.x);
    EXPECT_EQ(ta->Vel().y, v.y);
    EXPECT_EQ(ta->AngVelLocal().y, w.y);
    EXPECT_EQ(ta->AngVelLocal().z, w.z);
}
