// Counts past what 32-bit indices address (runtime/IndexLimits.h) are a deme::Error that names the
// call, the count and what it counts, never a wrapped count. (The counts themselves are taken in 64
// bits where detection makes them: CudaPrimitives.SumsCountsIn64Bits on a GPU, the CPU's in size_t.)
#include <gtest/gtest.h>

#include <string>

#include <deme/Error.h>

#include "runtime/IndexLimits.h"

using namespace deme;

TEST(IndexLimits, CountsUpTo32BitsPassAndOneMoreIsANamedError) {
    EXPECT_NO_THROW(requireIndexable(0, "contact pairs", FEWER_PAIRS_REMEDY, "DoDynamics"));
    EXPECT_NO_THROW(requireIndexable(4294967295ull, "contact pairs", FEWER_PAIRS_REMEDY, "DoDynamics"));
    try {
        requireIndexable(4294967296ull, "contact pairs", FEWER_PAIRS_REMEDY, "DoDynamics");
        FAIL() << "no error";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind("DoDynamics: 4294967296 contact pairs are more than the 4294967295", 0), 0u) << m;
        EXPECT_NE(m.find("SetMaxVelocity"), std::string::npos) << m;
    }
    // Six pairs a sphere, as Initialize assumes: 715,827,882 spheres pass, one more does not.
    EXPECT_NO_THROW(requireIndexable(6ull * 715827882ull, "contact pairs assumed (6 a sphere)", TOO_MANY_SPHERES_REMEDY,
                                     "Initialize"));
    EXPECT_THROW(requireIndexable(6ull * 715827883ull, "contact pairs assumed (6 a sphere)", TOO_MANY_SPHERES_REMEDY,
                                  "Initialize"),
                 Error);
    EXPECT_THROW(requireIndexable(1ull << 40, "bin entries", FEWER_BIN_ENTRIES_REMEDY, "DoDynamics"), Error);
}

// A GPU set indexes its pairs in 64 bits, bounded by the late table's 33-bit pair (state/HistorySlot.h):
// 2^33 - 2 pass (a billion spheres' six pairs each among them), one more is a named error.
TEST(IndexLimits, GpuSetsPassTwoToTheThirtyTwoPairsUpToTheLateTablesBound) {
    EXPECT_NO_THROW(requireGpuPairCount(6000000000ull, "Initialize"));
    EXPECT_NO_THROW(requireGpuPairCount((1ull << 33) - 2, "DoDynamics"));
    try {
        requireGpuPairCount((1ull << 33) - 1, "DoDynamics");
        FAIL() << "no error";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind("DoDynamics: 8589934591 contact pairs are more than the 8589934590", 0), 0u) << m;
        EXPECT_NE(m.find("SetMaxVelocity"), std::string::npos) << m;
    }
}
