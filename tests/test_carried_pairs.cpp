// Before a synchronous detection both backends keep only the pairs of the set in use that hand
// something to the next set (backend/cpu/CarriedPairs.h; on the GPU CudaDynamics::beforeDetectNow,
// whose kernels test_cuda_history_mapping.cpp holds to the CPU's choice): a history that is not all
// +0, a mesh state, the persistent flag. Checked on a hand-made set (which pairs stay, in order,
// with their history, in both history forms; when nothing is dropped), and on whole runs, which
// must be the same bit for bit with every pair kept (DEME_KEEP_WHOLE_SET=1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "BackendFixture.h"
#include "TestHelpers.h"
#include "backend/cpu/CarriedPairs.h"
#include "backend/cpu/HistoryForm.h"
#include "state/SimState.h"

using namespace deme;
using namespace deme_test;

namespace {

constexpr unsigned int W = 2;

// Ten sphere pairs (i, i + 1) with no history, but for pair 2 (a history), 5 (persistent), 7 (a
// mesh state) and 8 (a history of -0, which is one: the dense form keeps it bit for bit).
SimState handMadeSet() {
    SimState s;
    s.numWildcards = W;
    ContactArrays& c = s.contacts;
    for (bodyID_t i = 0; i < 10; i++) {
        c.geomA.push_back(i);
        c.geomB.push_back(i + 1);
        c.persistent.push_back(i == 5);
        c.meshState.push_back(i == 7 ? 1 : 0);
        c.wildcards.push_back(i == 2 ? 1.5f : i == 8 ? -0.f : 0.f);
        c.wildcards.push_back(i == 2 ? -2.5f : 0.f);
    }
    return s;
}

const std::vector<bodyID_t> kCarried = {2, 5, 7, 8};

void expectCarriedPairsOnly(const ContactArrays& c) {
    ASSERT_EQ(c.size(), kCarried.size());
    for (size_t k = 0; k < kCarried.size(); k++) {
        EXPECT_EQ(c.geomA[k], kCarried[k]);
        EXPECT_EQ(c.geomB[k], kCarried[k] + 1);
        EXPECT_EQ(c.persistent[k], kCarried[k] == 5 ? 1 : 0);
        EXPECT_EQ(c.meshState[k], kCarried[k] == 7 ? 1 : 0);
    }
}

}  // namespace

TEST(CarriedPairs, KeepsThePairsThatHandSomethingWithTheirHistoryDense) {
    SimState s = handMadeSet();
    ASSERT_TRUE(keepOnlyCarriedPairs(s));
    expectCarriedPairsOnly(s.contacts);
    const std::vector<float>& h = s.contacts.wildcards;
    ASSERT_EQ(h.size(), kCarried.size() * W);
    EXPECT_EQ(h[0], 1.5f);
    EXPECT_EQ(h[1], -2.5f);
    EXPECT_TRUE(std::signbit(h[6]));  // pair 8's -0
    EXPECT_EQ(h[2] + h[3] + h[4] + h[5] + h[7], 0.f);
}

TEST(CarriedPairs, KeepsThePairsThatHandSomethingWithTheirHistoryPooled) {
    SimState s = handMadeSet();
    const ScopedEnvironmentVariable pooled("DEME_CONTACT_HISTORY", "pooled");
    chooseHistoryForm(s);
    ASSERT_TRUE(s.contacts.historyPooled(W));
    ASSERT_TRUE(keepOnlyCarriedPairs(s));
    expectCarriedPairsOnly(s.contacts);
    ASSERT_TRUE(s.contacts.historyPooled(W));
    densifyHistory(s);
    const std::vector<float>& h = s.contacts.wildcards;
    ASSERT_EQ(h.size(), kCarried.size() * W);
    EXPECT_EQ(h[0], 1.5f);
    EXPECT_EQ(h[1], -2.5f);
    EXPECT_TRUE(std::signbit(h[6]));
    EXPECT_EQ(h[2] + h[3] + h[4] + h[5] + h[7], 0.f);
}

// A set that keeps A as runs (backend/cpu/ContactARuns.h: sphere o is owner o, geomA let go) makes A
// for the kept pairs only, from the runs, and holds geomA again.
TEST(CarriedPairs, KeepsThePairsThatHandSomethingWhereAIsKeptAsRuns) {
    SimState s = handMadeSet();
    ContactArrays& c = s.contacts;
    c.ownerAStart.clear();
    for (uint32_t o = 0; o <= 11; o++) c.ownerAStart.push_back(std::min(o, 10u));  // pair i's A is owner i
    std::vector<bodyID_t>().swap(c.geomA);
    c.aAsRuns = true;
    ASSERT_TRUE(keepOnlyCarriedPairs(s));
    EXPECT_FALSE(c.aAsRuns);
    expectCarriedPairsOnly(c);
    EXPECT_EQ(c.wildcards.size(), kCarried.size() * W);
    EXPECT_EQ(c.wildcards[0], 1.5f);
}

// Nothing dropped: where a contact-init rule gives new pairs values (a found pair of zeros keeps its
// zeros: dropping it would hand it the rule's), where most pairs carry something (the copies would
// cost a pass for little), and where DEME_KEEP_WHOLE_SET=1 says so.
TEST(CarriedPairs, KeepsEveryPairWhereDroppingWouldChangeOrSaveNothing) {
    SimState ruled = handMadeSet();
    ruled.wildcards.contactInit.push_back(ContactInitRule{0, 0, 1, 0.25f});
    EXPECT_FALSE(keepOnlyCarriedPairs(ruled));
    EXPECT_EQ(ruled.contacts.size(), 10u);

    SimState busy = handMadeSet();
    for (size_t i = 0; i < 10; i += 2) busy.contacts.persistent[i] = 1;  // 5 more carry: 8 of 10
    EXPECT_FALSE(keepOnlyCarriedPairs(busy));
    EXPECT_EQ(busy.contacts.size(), 10u);

    SimState whole = handMadeSet();
    const ScopedEnvironmentVariable keep("DEME_KEEP_WHOLE_SET", "1");
    EXPECT_FALSE(keepOnlyCarriedPairs(whole));
    EXPECT_EQ(whole.contacts.size(), 10u);
}

namespace {

constexpr float R = 0.004f;
constexpr double DT = 2e-5;

// Spheres on a lattice a little wider than their diameter, without gravity in a walled box, moving
// along x in chains (each row's spheres towards and away from their neighbours in turn, each row at
// its own speed), detected synchronously: most pairs of the set in use are apart (the rows side by
// side keep their distance), and pairs start to touch as the run goes on. A sphere touches at most
// its two neighbours in its row, so the GPU's atomic sums of its loads do not depend on their
// order, and runs compare bit for bit on both backends.
struct DriftingLattice {
    DEMSolver sim;
    std::shared_ptr<DEMTracker> grains;
    size_t n = 0;
    DriftingLattice() {
        sim.SetVerbosity("QUIET");
        auto mat = sim.LoadMaterial({{"E", 1e7}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}});
        sim.InstructBoxDomainDimension(0.12f, 0.12f, 0.12f);
        sim.InstructBoxDomainBoundingBC("all", mat);
        auto type = sim.LoadSphereType(0.0005f, R, mat);
        std::vector<float3> pts, v;
        for (int k = 0; k < 8; k++)
            for (int j = 0; j < 8; j++)
                for (int i = 0; i < 8; i++) {
                    pts.push_back(make_float3(i - 3.5f, j - 3.5f, k - 3.5f) * (2.05f * R));
                    const float speed = 0.3f * (1.f + 0.1f * (float)((j + 3 * k) % 5));
                    v.push_back(make_float3(i % 2 ? -speed : speed, 0.f, 0.f));
                }
        auto batch = sim.AddClumps(type, pts);
        batch->SetVel(v);
        n = pts.size();
        sim.SetInitTimeStep(DT);
        sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
        sim.SetMaxVelocity(0.5f);
        sim.SetCDUpdateFreq(10);
        sim.DisableAdaptiveUpdateFreq();
        sim.SetSynchronousContactDetection(true);
        sim.Initialize();
        grains = sim.Track(batch);
    }
    std::vector<float3> positions() {
        std::vector<float3> p(n);
        grains->Positions(p.data());
        return p;
    }
};

// 200 steps, an installation refused for memory (a margin forty times wider), 200 steps with the
// margin back; the positions after each part and after a restart from a checkpoint written at the
// failure.
std::vector<std::vector<float3>> runWithARefusedInstallation(const std::string& ckpt, bool gpu) {
    DriftingLattice b;
    std::vector<std::vector<float3>> out;
    b.sim.DoDynamics(200 * DT);
    out.push_back(b.positions());
    const MemoryStats m = b.sim.GetMemoryStats();
    const size_t held = gpu ? m.deviceTotal() : m.hostTotal();
    b.sim.SetMaxVelocity(20.f);
    {
        const ScopedEnvironmentVariable limit("DEME_MEMORY_LIMIT", std::to_string(held + 2000));
        const std::string msg = demeErrorMessage([&] { b.sim.DoDynamics(200 * DT); });
        EXPECT_NE(msg.find("the contact set has grown to "), std::string::npos) << msg;
    }
    out.push_back(b.positions());
    b.sim.WriteCheckpoint(ckpt);
    b.sim.SetMaxVelocity(0.5f);
    b.sim.DoDynamics(200 * DT);
    out.push_back(b.positions());
    DriftingLattice restarted;
    restarted.sim.ReadCheckpoint(ckpt);
    restarted.sim.SetMaxVelocity(0.5f);
    restarted.sim.DoDynamics(200 * DT);
    out.push_back(restarted.positions());
    return out;
}

size_t differing(const std::vector<float3>& a, const std::vector<float3>& b) {
    size_t d = 0;
    for (size_t k = 0; k < a.size(); k++) d += a[k].x != b[k].x || a[k].y != b[k].y || a[k].z != b[k].z;
    return d;
}

}  // namespace

// A synchronous detection whose installation is refused after the set in use lost its pairs that
// hand nothing on: the run detects afresh before its next step, and goes on as a run that kept the
// whole set (bit for bit); a checkpoint written then holds no set to go on with, and its restart
// goes on the same way.
DEME_BACKEND_TEST_SUITE(CarriedPairsRuns);

DEME_BACKEND_TEST(CarriedPairsRuns, ARefusedInstallationLeavesARunThatGoesOnAsWithTheWholeSet) {
    const ScopedEnvironmentVariable large("DEME_SMALL_CONTACT_SET_BYTES", "0");  // the GPU trims this small set too
    const std::vector<std::vector<float3>> trimmed =
        runWithARefusedInstallation((scratchDir() / "trimmed.ckpt").string(), onGpu());
    std::vector<std::vector<float3>> whole;
    {
        const ScopedEnvironmentVariable keep("DEME_KEEP_WHOLE_SET", "1");
        whole = runWithARefusedInstallation((scratchDir() / "whole.ckpt").string(), onGpu());
    }
    for (size_t k = 0; k < trimmed.size(); k++) EXPECT_EQ(differing(trimmed[k], whole[k]), 0u) << "part " << k;
    EXPECT_EQ(differing(trimmed[3], trimmed[2]), 0u);  // the restart goes on as the run did
    EXPECT_GT(differing(trimmed[2], trimmed[1]), 0u);  // the grains moved
}

// Between synchronous detections a GPU run holds no outbox (the id arrays a detection fills, which
// an installation leaves holding the old set's pairs) where it is large: DEME_SMALL_CONTACT_SET_BYTES
// sets the bound in bytes (0: every outbox goes). The contacts group then holds less, and the run is the
// same bit for bit. The CPU has no outbox: the same bytes.
DEME_BACKEND_TEST(CarriedPairsRuns, SynchronousRunsLetALargeOutboxGo) {
    // The whole set kept before each detection: otherwise the outbox holds the trimmed set's pairs.
    const ScopedEnvironmentVariable whole("DEME_KEEP_WHOLE_SET", "1");
    auto run = [&](const char* keepUpTo, size_t& contactBytes) {
        const ScopedEnvironmentVariable keep("DEME_SMALL_CONTACT_SET_BYTES", keepUpTo);
        DriftingLattice b;
        b.sim.DoDynamics(200 * DT);
        const MemoryStats m = b.sim.GetMemoryStats();
        contactBytes = (onGpu() ? m.deviceBytes : m.hostBytes)[(int)MemoryGroup::CONTACTS];
        return b.positions();
    };
    size_t kept = 0, released = 0;
    const std::vector<float3> a = run("1000000000000", kept), b = run("0", released);
    EXPECT_EQ(differing(a, b), 0u);
    if (onGpu())
        EXPECT_LT(released, kept);
    else
        EXPECT_EQ(released, kept);
}

// Between synchronous detections nothing of detection's stays where it is large: no bins, no
// per-sphere counts, and on the GPU no snapshot of the state (a synchronous detection on one GPU
// reads the state where it is, as the CPU's does). DEME_SMALL_CONTACT_SET_BYTES sets the bound (0:
// everything goes). The run is the same bit for bit. On the GPU a run that detected asynchronously
// first lets its snapshot go at the first synchronous detection (the CPU's worker thread keeps its
// buffers: docs/memory.md).
DEME_BACKEND_TEST(CarriedPairsRuns, SynchronousRunsLetLargeDetectionScratchGo) {
    auto detectionBytes = [&](DEMSolver& sim) {
        const MemoryStats m = sim.GetMemoryStats();
        return (onGpu() ? m.deviceBytes : m.hostBytes)[(int)MemoryGroup::DETECTION];
    };
    auto run = [&](const char* keepUpTo, size_t& held) {
        const ScopedEnvironmentVariable keep("DEME_SMALL_CONTACT_SET_BYTES", keepUpTo);
        DriftingLattice b;
        b.sim.DoDynamics(200 * DT);
        held = detectionBytes(b.sim);
        return b.positions();
    };
    size_t kept = 0, released = 0;
    const std::vector<float3> a = run("1000000000000", kept), b = run("0", released);
    EXPECT_EQ(differing(a, b), 0u);
    // What detection reads and never changes stays: on the GPU kT's copy of the family rules (a
    // byte per pair of families and a margin per family) and of the walls.
    const size_t unchanging = onGpu() ? NUM_FAMILIES * NUM_FAMILIES + NUM_FAMILIES * sizeof(float) + 1024 : 0;
    EXPECT_LE(released, unchanging);
    EXPECT_GE(kept, released + 512 * sizeof(uint32_t));  // the bins' entries at least (512 spheres)

    // And the owners' travel at an asynchronous order (4 B each), which a synchronous set's
    // installation does not need (it counts from zero).
    const ScopedEnvironmentVariable keep("DEME_SMALL_CONTACT_SET_BYTES", "0");
    DriftingLattice switched;
    switched.sim.SetSynchronousContactDetection(false);
    switched.sim.DoDynamics(200 * DT);
    const size_t ownersAsync = switched.sim.GetMemoryStats().device(MemoryGroup::OWNER_STATE);
    // The snapshot: the grains' compact positions (state/OwnerCentre.h) at least.
    if (onGpu()) EXPECT_GE(detectionBytes(switched.sim), switched.n * (sizeof(voxelID_t) + 3 * sizeof(subVoxelPos_t)));
    switched.sim.SetSynchronousContactDetection(true);
    switched.sim.DoDynamics(200 * DT);
    if (onGpu()) {
        EXPECT_LE(detectionBytes(switched.sim), unchanging);
        const size_t freed = ownersAsync - switched.sim.GetMemoryStats().device(MemoryGroup::OWNER_STATE);
        EXPECT_GE(freed, switched.n * sizeof(float));        // every grain's ...
        EXPECT_LE(freed, (switched.n + 8) * sizeof(float));  // ... and the walls' owner
    }
}

// The memory check before each installation counts the new set in the form it will take: after a
// trim the set in use holds only the pairs with a history, but the new set is expected to have the
// share the whole set had (a pooled history, not a dense one). A run whose sets keep their size goes
// on under a limit a little above what it holds.
DEME_BACKEND_TEST(CarriedPairsRuns, ChecksAfterATrimCountTheWholeSetsShare) {
    // The GPU trims this small set too. (The CPU trims it anyway, and keeps its bins, as a run of
    // this size does: the room below is measured with them.)
    const ScopedEnvironmentVariable large("DEME_SMALL_CONTACT_SET_BYTES", onGpu() ? "0" : "1000000000000");
    // (Every set pooled on the GPU, whose automatic choice keeps small sets dense; the CPU's own
    // choice, which pools sets whose pairs are mostly apart.)
    const ScopedEnvironmentVariable pooled("DEME_POOLED_HISTORY", "1");
    DriftingLattice b;
    b.sim.DoDynamics(200 * DT);
    const MemoryStats m = b.sim.GetMemoryStats();
    const size_t held = onGpu() ? m.deviceTotal() : m.hostTotal();
    const size_t contacts = (onGpu() ? m.deviceBytes : m.hostBytes)[(int)MemoryGroup::CONTACTS];
    // On the CPU room for sets a third larger than the one held: not for their history dense (24
    // bytes a pair against 8 or so pooled). On the GPU an installation holds two sets (and two
    // pools, each with at least 4,096 spare slots: at this size the check's bytes are the pools',
    // whatever the share), so room for a second set of the size held: what a run whose sets keep
    // their size needs.
    const ScopedEnvironmentVariable limit("DEME_MEMORY_LIMIT",
                                          std::to_string(held + (onGpu() ? contacts : contacts / 3)));
    b.sim.DoDynamics(400 * DT);
    EXPECT_NEAR(b.sim.GetSimTime(), 600 * DT, 1e-9);
}
