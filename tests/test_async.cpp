// The asynchronous kinematics thread: delayed contact sets must never change the physics.
//
// Tolerance: none. A contact set only decides which pairs the force pass looks at; pairs apart get
// zero force and cleared history, and every owner sums its contacts in key order. So as long as no
// touching pair is ever missing, the trajectory is bit-identical to detecting every step; any
// missed contact would show up as a difference.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "TestHelpers.h"
#include "runtime/UpdateFrequency.h"

using namespace deme;
using namespace deme_test;

namespace {

enum class Mode { EVERY_STEP, SYNC, ASYNC };

struct Scenario {
    bool projectile = false;  // a 10 m/s ball shot into the bed
    bool shaken = false;      // the container oscillates hard
};

// A bed of ~600 spheres in a box; returns all clump states after the run.
std::vector<float> run(const Scenario& sc, Mode mode, unsigned int freq = 20, int calls = 1) {
    DEMSolver sim;
    sim.SetBackend("cpu");  // the CPU threads are under test, bit for bit
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.4, 0.5, 0.01));
    sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.4f);
    auto box = sim.AddExternalObject();
    box->AddPlane(make_float3(0, 0, -0.06f), make_float3(0, 0, 1), mat);
    box->AddPlane(make_float3(-0.04f, 0, 0), make_float3(1, 0, 0), mat);
    box->AddPlane(make_float3(0.04f, 0, 0), make_float3(-1, 0, 0), mat);
    box->AddPlane(make_float3(0, -0.04f, 0), make_float3(0, 1, 0), mat);
    box->AddPlane(make_float3(0, 0.04f, 0), make_float3(0, -1, 0), mat);
    if (sc.shaken) {
        box->SetFamily(5);
        sim.SetFamilyPrescribedLinVel(5, "0.3*sin(200*t)", "0", "0.6*cos(150*t)");
    }
    auto pts = HCPSampler(0.0082f).SampleBox(make_float3(0, 0, -0.03f), make_float3(0.035f, 0.035f, 0.025f));
    auto grains = sim.AddClumps(sim.LoadSphereType((float)sphereMass(0.004, 2600), 0.004f, mat), pts);
    std::shared_ptr<DEMClumpBatch> ball;
    if (sc.projectile) {
        ball = sim.AddClumps(sim.LoadSphereType((float)sphereMass(0.006, 7800), 0.006f, mat),
                             {make_float3(0.001f, -0.002f, 0.03f)});
        ball->SetVel(make_float3(0.5f, 0.3f, -10.f));
    }
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetInitTimeStep(1e-5);
    sim.SetSynchronousContactDetection(mode != Mode::ASYNC);
    sim.SetCDUpdateFreq(mode == Mode::EVERY_STEP ? 1 : freq);
    sim.Initialize();
    const double total = 0.02;
    for (int c = 0; c < calls; c++) sim.DoDynamics(total / calls);
    std::vector<float> out;
    auto tr = sim.Track(grains);
    for (size_t i = 0; i < pts.size(); i++) {
        const float3 p = tr->Pos(i), v = tr->Vel(i), w = tr->AngVelLocal(i);
        out.insert(out.end(), {p.x, p.y, p.z, v.x, v.y, v.z, w.x, w.y, w.z});
    }
    if (ball) {
        const float3 p = sim.Track(ball)->Pos();
        out.insert(out.end(), {p.x, p.y, p.z});
    }
    return out;
}

}  // namespace

TEST(Async, FastProjectileMissesNoContact) {
    Scenario sc;
    sc.projectile = true;
    const auto ref = run(sc, Mode::EVERY_STEP);
    EXPECT_LT(ref[ref.size() - 1], 0.01f);  // the ball reached the bed (its top is near z = 0)
    EXPECT_EQ(run(sc, Mode::ASYNC), ref);
    EXPECT_EQ(run(sc, Mode::SYNC, 50), ref);
}

TEST(Async, ShakenBedMissesNoContact) {
    Scenario sc;
    sc.shaken = true;
    const auto ref = run(sc, Mode::EVERY_STEP);
    EXPECT_EQ(run(sc, Mode::ASYNC), ref);
    EXPECT_EQ(run(sc, Mode::ASYNC, 5), ref);
}

// 2000 DoDynamics calls of one step each give what one call of 2000 steps gives.
TEST(Async, ManyShortCallsEqualOneLongCall) {
    Scenario sc;
    sc.shaken = true;
    const auto ref = run(sc, Mode::ASYNC, 20, 1);
    EXPECT_EQ(run(sc, Mode::ASYNC, 20, 2000), ref);
}

// Asynchronous and synchronous modes agree on the incline regimes' end state (bit for bit).
TEST(Async, InclineAgreesWithSynchronous) {
    auto endState = [](bool sync) {
        DEMSolver sim;
        sim.SetBackend("cpu");  // the CPU threads are under test, bit for bit
        sim.SetVerbosity("QUIET");
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.25, 0.05));
        sim.InstructBoxDomainDimension(80, 4, 4);
        sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
        auto ball = sim.AddClumps(sim.LoadSphereType(5.f, 0.2f, mat), {make_float3(30.f, 0, 0.1995f)});
        ball->SetVel(make_float3(0.5f, 0, 0));
        const float a = 20.f * (float)deme::PI / 180.f;
        sim.SetGravitationalAcceleration(make_float3(-9.81f * std::sin(a), 0, -9.81f * std::cos(a)));
        sim.SetInitTimeStep(1e-4);
        sim.SetSynchronousContactDetection(sync);
        sim.Initialize();
        sim.DoDynamics(1.0);
        auto tr = sim.Track(ball);
        return std::vector<float>{tr->Pos().x, tr->Vel().x, tr->AngVelLocal().y};
    };
    const auto sync = endState(true);
    EXPECT_LT(sync[1], -0.1f);  // rolling down: 20 deg is between atan(Crr) and atan(3.5 mu - 2.5 Crr)
    EXPECT_EQ(endState(false), sync);
}

// The n_max controller: converges to 2.25 x latency + 2 (never below the user's floor, never above
// the cap), and orders a successor early enough to arrive before the set in use runs out.
TEST(Async, UpdateFrequencyAdaptsToLatency) {
    UpdateFrequency f;
    f.configure(5, 100, true);
    EXPECT_EQ(f.orderAge(), 0u);  // no latency measured yet: order at once
    for (int i = 0; i < 60; i++) f.observeLatency(12);
    EXPECT_NEAR(f.smoothedLatency(), 12.0, 1e-3);
    EXPECT_EQ(f.nMax(), 29u);            // ceil(2.25 x 12) + 2
    EXPECT_EQ(f.orderAge(), 29u - 16u);  // lead ceil(1.25 x 12) + 1 = 16 steps
    for (int i = 0; i < 60; i++) f.observeLatency(1);
    EXPECT_EQ(f.nMax(), 5u);  // the floor
    for (int i = 0; i < 60; i++) f.observeLatency(500);
    EXPECT_EQ(f.nMax(), 100u);  // the cap
    UpdateFrequency fixed;
    fixed.configure(7, 100, false);
    fixed.observeLatency(50);
    EXPECT_EQ(fixed.nMax(), 7u);
}

// Detection on the dynamics' device (one GPU, two streams): the cost balance of the synchronous mode
// takes the floor's place, and the latency bound ceil(2.25 L) + 2 stays the lower limit. Same
// figures as the synchronous test below: D = 54 ms, F = 6.7 ms per step, 6.6 % false positives at
// n = 20 give the optimum 70, in doublings.
TEST(Async, SharedDeviceUpdateFrequencyBalancesCostAboveTheLatencyBound) {
    UpdateFrequency f;
    f.configure(20, 200, true, true);
    for (int i = 0; i < 60; i++) f.observeLatency(4);
    EXPECT_EQ(f.nMax(), 20u);  // the cost balance starts at the user's value
    f.observeSharedCost(0.054, 0.0067, 0.066);
    EXPECT_EQ(f.nMax(), 40u);
    f.observeSharedCost(0.054, 0.0067, 0.066 * 40 / 20);
    EXPECT_EQ(f.nMax(), 70u);
    // Detection becomes cheap: n_max halves per result down to the latency bound, not the floor.
    for (int i = 0; i < 10; i++) f.observeSharedCost(1e-6, 0.0067, 0.066 * f.nMax() / 20);
    EXPECT_EQ(f.nMax(), 11u);  // ceil(2.25 x 4) + 2
    for (int i = 0; i < 60; i++) f.observeLatency(40);
    EXPECT_EQ(f.nMax(), 92u);  // the latency needs more than the balance
    // kT on its own device (or the CPU): the cost is not weighed, the floor holds.
    UpdateFrequency own;
    own.configure(20, 200, true, false);
    own.observeSharedCost(0.054, 0.0067, 0.066);
    EXPECT_EQ(own.nMax(), 20u);
    for (int i = 0; i < 60; i++) own.observeLatency(4);
    EXPECT_EQ(own.nMax(), 20u);
}

// Repeated solvers: threads start and stop cleanly, also when a run ends in an error.
TEST(Async, WorkerShutsDownAfterErrors) {
    for (int i = 0; i < 20; i++) {
        DEMSolver sim;
        sim.SetBackend("cpu");  // the CPU threads are under test, bit for bit
        sim.SetVerbosity("QUIET");
        auto mat = sim.LoadMaterial(material(1e9, 0.3, 0.5, 0.3));
        sim.InstructBoxDomainDimension(1, 1, 1);
        auto t = sim.LoadSphereType(1e-3f, 0.01f, mat);
        sim.AddClumps(t, {make_float3(0, 0, 0), make_float3(0.005f, 0, 0)});  // deep overlap: explodes
        sim.SetErrorOutVelocity(1.f);
        sim.SetInitTimeStep(1e-5);
        sim.Initialize();
        EXPECT_THROW(sim.DoDynamics(0.01), deme::Error);
    }
}

// A small case for the ThreadSanitizer run (ctest tsan_threading): a few dozen grains poured into a
// shaken box, asynchronous against every-step detection, over several DoDynamics calls.
TEST(Async, SmallShakenBoxThreadsAgree) {
    auto runSmall = [](bool async) {
        DEMSolver sim;
        sim.SetBackend("cpu");  // the CPU threads are under test, bit for bit
        sim.SetVerbosity("QUIET");
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.4, 0.5));
        sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.1f);
        auto box = sim.AddExternalObject();
        box->AddPlane(make_float3(0, 0, -0.03f), make_float3(0, 0, 1), mat);
        box->AddCylinder(make_float3(0), make_float3(0, 0, 1), 0.02f, mat, 0);
        box->SetFamily(5);
        sim.SetFamilyPrescribedLinVel(5, "0.3*sin(300*t)", "0", "0");
        auto pts = HCPSampler(0.0085f).SampleCylinderZ(make_float3(0, 0, -0.01f), 0.015f, 0.015f);
        auto g = sim.AddClumps(sim.LoadSphereType((float)sphereMass(0.004, 2600), 0.004f, mat), pts);
        sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
        sim.SetInitTimeStep(2e-5);
        sim.SetSynchronousContactDetection(!async);
        sim.SetCDUpdateFreq(async ? 5 : 1);
        sim.Initialize();
        for (int i = 0; i < 10; i++) sim.DoDynamicsThenSync(0.001);
        std::vector<float> out;
        auto tr = sim.Track(g);
        for (size_t i = 0; i < pts.size(); i++) out.insert(out.end(), {tr->Pos(i).x, tr->Pos(i).z, tr->Vel(i).x});
        return out;
    };
    const auto ref = runSmall(false);
    ASSERT_GT(ref.size(), 20u);
    EXPECT_EQ(runSmall(true), ref);
}

// Synchronous mode: n_max balances the detection cost D/n against false positives growing with n;
// with D = 54 ms, F = 6.7 ms per step and 6.6 % false positives at n = 20 (the CPU-BED figures),
// the optimum is sqrt(D n / (F/2 phi)) = 70, reached in at most a doubling per detection.
TEST(Async, SyncUpdateFrequencyBalancesDetectionAndFalsePositives) {
    UpdateFrequency f;
    f.configure(20, 200, true);
    f.observeSyncCost(0.054, 0.0067, 0.066);
    EXPECT_EQ(f.nMax(), 40u);  // capped at a doubling
    f.observeSyncCost(0.054, 0.0067, 0.066 * 40 / 20);
    EXPECT_EQ(f.nMax(), 70u);
    f.observeSyncCost(0.054, 0.0067, 0.066 * 70 / 20);
    EXPECT_EQ(f.nMax(), 70u);  // stays at the optimum
    UpdateFrequency fixed;
    fixed.configure(20, 200, false);
    fixed.observeSyncCost(0.054, 0.0067, 0.066);
    EXPECT_EQ(fixed.nMax(), 20u);
}
