// The memory estimate of Initialize (runtime/MemoryEstimate.h, docs/memory.md "Scenes too large"):
// it predicts the table GetMemoryStats measures once the run has its contact set, and a scene whose
// estimate exceeds the memory there (here a smaller machine made by DEME_MEMORY_LIMIT) fails at
// Initialize with a deme::Error that says what it needs and what there is.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "BackendFixture.h"
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
