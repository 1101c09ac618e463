// The memory estimate of Initialize (runtime/MemoryEstimate.h, docs/memory.md "Scenes too large"):
// it predicts the table GetMemoryStats measures once the run has its contact set, and a scene whose
// estimate exceeds the memory there (here a smaller machine made by DEME_MEMORY_LIMIT) fails at
// Initialize with a deme::Error that says what it needs and what there is; a contact set that
// outgrows the memory later fails DoDynamics before it is installed, and the run can be saved.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "BackendFixture.h"
#include "ForceModelTestUtil.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(MemoryEstimate);

// The estimate against the table after the bed settled, where the steps keep their arrays (the
// device on the GPU, the host on the CPU). Owners and geometry are counted from the same field
// lists and counts: within 10 %. The whole, which assumes six pairs per sphere for a set whose size
// the estimate cannot know: within a factor of two of what the settled bed holds.
DEME_BACKEND_TEST(MemoryEstimate, InitializeEstimatesWhatTheRunHolds) {
    DEMSolver sim;
    addThousandSphereBed(sim);
    sim.Initialize();
    sim.DoDynamics(0.3);
    ASSERT_GT(sim.GetNumContacts(), 500u);  // settled into a bed
    const MemoryStats m = sim.GetMemoryStats();
    const size_t* held = onGpu() ? m.deviceBytes : m.hostBytes;
    EXPECT_EQ(m.estimatedPairs, 6000u);  // six per sphere
    for (MemoryGroup g : {MemoryGroup::OWNER_STATE, MemoryGroup::GEOMETRY}) {
        const double est = (double)m.estimatedBytes[(int)g], real = (double)held[(int)g];
        EXPECT_NEAR(est, real, 0.1 * real) << memoryGroupName(g);
    }
    EXPECT_GT(m.estimatedBytes[(int)MemoryGroup::CONTACTS], 0u);
    EXPECT_GT(m.estimatedBytes[(int)MemoryGroup::DETECTION], 0u);
    const double real = (double)(onGpu() ? m.deviceTotal() : m.hostTotal() - m.host(MemoryGroup::OUTPUT));
    EXPECT_GT((double)m.estimatedTotal(), 0.5 * real);
    EXPECT_LT((double)m.estimatedTotal(), 2.0 * real);
}

// A machine with less memory than the estimate: Initialize fails, naming the bytes needed and
// available and the groups, and leaves the solver as it was (Initialize again, with the limit
// lifted, runs); with enough it passes.
DEME_BACKEND_TEST(MemoryEstimate, SceneTooLargeFailsAtInitialize) {
    size_t estimate = 0;
    {
        DEMSolver sim;
        addThousandSphereBed(sim);
        sim.Initialize();
        estimate = sim.GetMemoryStats().estimatedTotal();
    }
    ASSERT_GT(estimate, 0u);
    {
        DEMSolver sim;
        addThousandSphereBed(sim);
        {
            const ScopedEnvironmentVariable limit("DEME_MEMORY_LIMIT", std::to_string(estimate / 2));
            const std::string msg = demeErrorMessage([&] { sim.Initialize(); });
            EXPECT_NE(msg.find("Initialize"), std::string::npos) << msg;
            EXPECT_NE(msg.find("needs about " + std::to_string(estimate) + " bytes"), std::string::npos) << msg;
            EXPECT_NE(msg.find(std::to_string(estimate / 2) + " (0."), std::string::npos) << msg;  // available
            EXPECT_NE(msg.find("contacts and history"), std::string::npos) << msg;
            EXPECT_NE(msg.find(onGpu() ? "GPU" : "host memory"), std::string::npos) << msg;
        }
        sim.Initialize();
        EXPECT_EQ(sim.GetNumClumps(), 1000u);
        sim.DoDynamics(1e-3);
    }
    {
        const ScopedEnvironmentVariable limit("DEME_MEMORY_LIMIT", std::to_string(estimate + 1));
        DEMSolver sim;
        addThousandSphereBed(sim);
        sim.Initialize();
        sim.DoDynamics(1e-3);
    }
}

// A limit that is not a number of bytes is an error, not ignored.
DEME_BACKEND_TEST(MemoryEstimate, MalformedLimitIsAnError) {
    const ScopedEnvironmentVariable limit("DEME_MEMORY_LIMIT", "12 GB");
    DEMSolver sim;
    addThousandSphereBed(sim);
    const std::string msg = demeErrorMessage([&] { sim.Initialize(); });
    EXPECT_NE(msg.find("DEME_MEMORY_LIMIT is \"12 GB\""), std::string::npos) << msg;
}

// A contact set that outgrows the memory during the run (here the margin widened after Initialize
// by SetMaxVelocity, on a machine made small by DEME_MEMORY_LIMIT: a little more than the run holds)
// fails DoDynamics before it is installed, with a deme::Error naming the set, its pairs and bytes,
// and what there is. Nothing has changed then: the state is that of the last step, WriteCheckpoint
// saves it, a solver that reads the checkpoint has the same time and positions, and with the limit
// lifted and the margin back the run goes on.
DEME_BACKEND_TEST(MemoryEstimate, ContactSetOutgrowingTheMemoryIsANamedErrorAndTheRunCanBeSaved) {
    const std::string ckpt = (scratchDir() / "saved.ckpt").string();
    std::vector<float3> saved(1000), read(1000);
    double savedTime = 0.0;
    {
        DEMSolver sim;
        auto bed = addThousandSphereBed(sim);
        sim.Initialize();
        auto grains = sim.Track(bed);
        sim.DoDynamics(0.02);
        const size_t pairsBefore = sim.GetNumContacts();
        const MemoryStats m = sim.GetMemoryStats();
        const size_t held = onGpu() ? m.deviceTotal() : m.hostTotal();
        // A margin of about 1.1 * 20 m/s * n_max * 2e-5 s: every grain within a few of its
        // neighbours' diameters is a pair, some ten times the set in use.
        sim.SetMaxVelocity(20.f);
        {
            const ScopedEnvironmentVariable limit("DEME_MEMORY_LIMIT", std::to_string(held + 50000));
            const std::string msg = demeErrorMessage([&] { sim.DoDynamics(0.02); });
            EXPECT_NE(msg.find("DoDynamics"), std::string::npos) << msg;
            EXPECT_NE(msg.find("the contact set has grown to "), std::string::npos) << msg;
            EXPECT_NE(msg.find("for contacts and history"), std::string::npos) << msg;
            EXPECT_NE(msg.find(onGpu() ? "GPU" : "host memory"), std::string::npos) << msg;
            EXPECT_NE(msg.find("WriteCheckpoint saves it"), std::string::npos) << msg;
            // The pairs named are many more than the set in use held.
            const size_t at = msg.find("grown to ") + 9;
            EXPECT_GT(std::stoull(msg.substr(at)), 5 * pairsBefore) << msg;
        }
        EXPECT_GT(sim.GetSimTime(), 0.02 - 1e-9);
        EXPECT_LT(sim.GetSimTime(), 0.04 - 1e-9);  // stopped in the call that failed
        savedTime = sim.GetSimTime();
        grains->Positions(saved.data());
        sim.WriteCheckpoint(ckpt);
        // The run goes on with the margin back and the limit lifted.
        sim.SetMaxVelocity(0.5f);
        sim.DoDynamics(0.01);
        EXPECT_NEAR(sim.GetSimTime(), savedTime + 0.01, 1e-9);
    }
    DEMSolver sim;
    auto bed = addThousandSphereBed(sim);
    sim.Initialize();
    sim.ReadCheckpoint(ckpt);
    EXPECT_EQ(sim.GetSimTime(), savedTime);
    sim.Track(bed)->Positions(read.data());
    for (size_t i = 0; i < saved.size(); i++) {
        EXPECT_EQ(read[i].x, saved[i].x) << i;
        EXPECT_EQ(read[i].z, saved[i].z) << i;
    }
}

// Initialize counts the first contact set in the form its history will take: none of the bed's
// pairs touch yet, so where the history is pooled (state/PooledHistory.h on the CPU by default;
// state/HistoryPool.h on the GPU, here for every set and without spare slots) the set holds no W
// floats per pair. A machine between the pooled estimate and the dense one starts and steps the
// pooled run and refuses the dense one, saying what it assumed.
DEME_BACKEND_TEST(MemoryEstimate, PooledHistoryIsCountedInItsForm) {
    const char* form = onGpu() ? "DEME_POOLED_HISTORY" : "DEME_CONTACT_HISTORY";
    const std::string pooled = onGpu() ? "1" : "auto", dense = onGpu() ? "0" : "dense";
    const ScopedEnvironmentVariable noSpare("DEME_HISTORY_POOL_SPARE", "0");
    auto estimate = [&](const std::string& value) {
        const ScopedEnvironmentVariable v(form, value);
        DEMSolver sim;
        addThousandSphereBed(sim);
        sim.Initialize();
        return sim.GetMemoryStats();
    };
    const MemoryStats p = estimate(pooled), d = estimate(dense);
    const int contacts = (int)MemoryGroup::CONTACTS;
    EXPECT_EQ(p.estimatedPairs, d.estimatedPairs);
    // Without its four floats of history per pair (Hertz-Mindlin's): 16 of the dense form's 20-30
    // bytes a pair on the CPU, 32 (two sets) of 52 on the GPU, which keeps a 4-byte slot per pair.
    EXPECT_LT((double)p.estimatedBytes[contacts], 0.75 * (double)d.estimatedBytes[contacts]);
    EXPECT_EQ(p.estimatedTotal() - p.estimatedBytes[contacts], d.estimatedTotal() - d.estimatedBytes[contacts]);

    const size_t between = (p.estimatedTotal() + d.estimatedTotal()) / 2;
    const ScopedEnvironmentVariable limit("DEME_MEMORY_LIMIT", std::to_string(between));
    {
        const ScopedEnvironmentVariable v(form, pooled);
        DEMSolver sim;
        addThousandSphereBed(sim);
        sim.Initialize();
        sim.DoDynamics(2e-3);
        EXPECT_NEAR(sim.GetSimTime(), 2e-3, 1e-9);
    }
    {
        const ScopedEnvironmentVariable v(form, dense);
        DEMSolver sim;
        addThousandSphereBed(sim);
        const std::string msg = demeErrorMessage([&] { sim.Initialize(); });
        EXPECT_NE(msg.find("needs about " + std::to_string(d.estimatedTotal()) + " bytes"), std::string::npos) << msg;
        EXPECT_EQ(msg.find("history pooled"), std::string::npos) << msg;
    }
    {
        const ScopedEnvironmentVariable v(form, pooled);
        const ScopedEnvironmentVariable small("DEME_MEMORY_LIMIT", std::to_string(p.estimatedTotal() / 2));
        DEMSolver sim;
        addThousandSphereBed(sim);
        const std::string msg = demeErrorMessage([&] { sim.Initialize(); });
        EXPECT_NE(msg.find("and their history pooled in 0 slots"), std::string::npos) << msg;
    }
}

// Where detection is synchronous, the set in use keeps only the pairs that hand something on before
// each detection (kinematics/CarriedPairsRule.h), and a GPU installation then holds one whole set
// and the few pairs kept instead of two whole sets: the estimate of a pooled set counts it so (the
// first set's pool has no slot in use here: one set's ids and slot bits, and the trim's marks, where
// asynchronous detection counts two sets'). Not with
// DEME_KEEP_WHOLE_SET=1 or asynchronous detection. The CPU holds one set either way.
DEME_BACKEND_TEST(MemoryEstimate, ASetTrimmedBeforeEachDetectionIsCountedOnce) {
    const ScopedEnvironmentVariable pooled(onGpu() ? "DEME_POOLED_HISTORY" : "DEME_CONTACT_HISTORY",
                                           onGpu() ? "1" : "auto");
    const ScopedEnvironmentVariable noSpare("DEME_HISTORY_POOL_SPARE", "0");
    // The GPU trims only sets over 32 MiB of ids unless told otherwise (CudaDynamics::m_smallSetBytes);
    // with a small set left whole, the estimate counts two sets as for asynchronous detection.
    const ScopedEnvironmentVariable large("DEME_SMALL_CONTACT_SET_BYTES", "0");
    auto contacts = [](bool sync, const char* keepWhole) {
        const ScopedEnvironmentVariable whole("DEME_KEEP_WHOLE_SET", keepWhole);
        DEMSolver sim;
        addThousandSphereBed(sim);
        sim.SetSynchronousContactDetection(sync);
        sim.Initialize();
        return sim.GetMemoryStats().estimatedBytes[(int)MemoryGroup::CONTACTS];
    };
    const size_t trimmed = contacts(true, "0"), whole = contacts(true, "1"), async = contacts(false, "0");
    EXPECT_EQ(whole, async);
    if (onGpu())
        EXPECT_LT((double)trimmed, 0.7 * (double)async);
    else
        EXPECT_EQ(trimmed, async);
}

// Both backends keep a persistent flag per pair only where the model may set one (a custom model)
// or a pair of the set has one (docs/memory.md, "Persistent flags only where used"): the estimate
// counts the byte only then. The default model and the same model written as a custom one assume
// the same pairs in the same form; the custom one's contacts are a byte more for each pair of every
// set the form holds (one or two sets, and the pairs kept by a trim), nothing else differs.
DEME_BACKEND_TEST(MemoryEstimate, PersistentFlagsAreCountedWhereTheModelMaySetThem) {
    // Both histories dense: a custom model's set never pools its history (DeviceForceModel::
    // poolsHistory), so a run that pools every set it may (the GPU suite's `pooled` step) would
    // compare two forms here.
    const ScopedEnvironmentVariable dense("DEME_POOLED_HISTORY", "0");
    auto estimate = [](bool custom) {
        DEMSolver sim;
        if (custom) declareHertzMindlinInputs(*sim.DefineContactForceModel(hertzMindlinSnippet()));
        addThousandSphereBed(sim);
        sim.Initialize();
        return sim.GetMemoryStats();
    };
    const MemoryStats builtIn = estimate(false), custom = estimate(true);
    const int contacts = (int)MemoryGroup::CONTACTS;
    ASSERT_EQ(builtIn.estimatedPairs, custom.estimatedPairs);
    const size_t pairs = builtIn.estimatedPairs,
                 more = custom.estimatedBytes[contacts] - builtIn.estimatedBytes[contacts];
    ASSERT_GT(custom.estimatedBytes[contacts], builtIn.estimatedBytes[contacts]);
    EXPECT_GE(more, pairs);
    EXPECT_LE(more, 2 * pairs);
    EXPECT_EQ(custom.estimatedTotal() - custom.estimatedBytes[contacts],
              builtIn.estimatedTotal() - builtIn.estimatedBytes[contacts]);
}
