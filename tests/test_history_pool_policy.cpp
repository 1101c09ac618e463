// The rule that decides which GPU contact sets keep their history pooled (runtime/HistoryPoolPolicy.h,
// docs/memory.md): by the environment's mode, the set's size and the share of its pairs with a
// history; the spare slots a pool gets; bad environment values are named errors.
#include <gtest/gtest.h>

#include <string>

#include <deme/Error.h>

#include "BackendFixture.h"
#include "runtime/HistoryPoolPolicy.h"

using namespace deme;
using deme_test::ScopedEnvironmentVariable;

TEST(HistoryPoolPolicy, ChoosesByModeSizeAndShareOfPairsWithAHistory) {
    HistoryPoolPolicy p;
    p.modelPools = true;
    p.W = 4;
    // auto: sets over 256 MiB of dense history (4 floats a pair: 16,777,216 pairs) are counted.
    const size_t bound = HistoryPoolPolicy::AUTO_MIN_DENSE_BYTES / (4 * sizeof(float));
    EXPECT_EQ(bound, 16777216u);
    EXPECT_FALSE(p.considers(bound));
    EXPECT_TRUE(p.considers(bound + 1));
    // ... and pooled where at most half their pairs keep a slot.
    EXPECT_TRUE(p.chooses(1000, 500));
    EXPECT_FALSE(p.chooses(1000, 501));
    // 1: every set, whatever the share; 0: none.
    p.mode = HistoryPoolPolicy::Mode::ALWAYS;
    EXPECT_TRUE(p.considers(1));
    EXPECT_TRUE(p.chooses(1000, 1000));
    EXPECT_FALSE(p.considers(0));
    p.mode = HistoryPoolPolicy::Mode::NEVER;
    EXPECT_FALSE(p.considers(bound * 4));
    // A model without a pooled pass, without history or with a history too long: never.
    p.mode = HistoryPoolPolicy::Mode::ALWAYS;
    p.modelPools = false;
    EXPECT_FALSE(p.considers(100));
    p.modelPools = true;
    p.W = 0;
    EXPECT_FALSE(p.considers(100));
    p.W = MAX_POOLED_HISTORY + 1;
    EXPECT_FALSE(p.considers(100));
}

TEST(HistoryPoolPolicy, SpareSlotsAreAQuarterASixtyFourthOfTheSetOrTheLeastAsked) {
    HistoryPoolPolicy p;  // the least: 4096
    EXPECT_EQ(p.capacityFor(0, 1000), 4096u);
    EXPECT_EQ(p.capacityFor(40000, 100000), 50000u);      // a quarter of the used
    EXPECT_EQ(p.capacityFor(40000, 64000000), 1040000u);  // a 64th of the set
    p.minSpare = 0;                                       // DEME_HISTORY_POOL_SPARE=0: none
    EXPECT_EQ(p.capacityFor(40000, 64000000), 40000u);
}

TEST(HistoryPoolPolicy, ReadsTheEnvironmentAndNamesBadValues) {
    {
        const ScopedEnvironmentVariable mode("DEME_POOLED_HISTORY", "1");
        const ScopedEnvironmentVariable spare("DEME_HISTORY_POOL_SPARE", "0");
        const HistoryPoolPolicy p = HistoryPoolPolicy::fromEnvironment();
        EXPECT_EQ(p.mode, HistoryPoolPolicy::Mode::ALWAYS);
        EXPECT_EQ(p.minSpare, 0u);
    }
    {
        const ScopedEnvironmentVariable mode("DEME_POOLED_HISTORY", "0");
        EXPECT_EQ(HistoryPoolPolicy::fromEnvironment().mode, HistoryPoolPolicy::Mode::NEVER);
    }
    for (const char* bad : {"yes", "2", "pooled"}) {
        const ScopedEnvironmentVariable mode("DEME_POOLED_HISTORY", bad);
        try {
            HistoryPoolPolicy::fromEnvironment();
            ADD_FAILURE() << bad << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("DEME_POOLED_HISTORY"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
        }
    }
    for (const char* bad : {"many", "-1", "12k", ""}) {
        const ScopedEnvironmentVariable spare("DEME_HISTORY_POOL_SPARE", bad);
        EXPECT_THROW(HistoryPoolPolicy::fromEnvironment(), Error) << "\"" << bad << "\"";
    }
}
