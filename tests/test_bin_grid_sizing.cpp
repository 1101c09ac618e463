// The default bin edge (kinematics/BinGridSizing): the detection-work estimate picks twice the radius
// of one sphere size, the small spheres' bins for a ball among many small grains, and the large
// spheres' bins when those dominate. (Which bins a detection uses never changes what it finds:
// ContactDetection.MatchesBruteForceExactly checks that for several edges, the default among them.)
#include <gtest/gtest.h>

#include <vector>

#include "kinematics/BinGridSizing.h"

using namespace deme;

TEST(BinGridSizing, OneSizeGivesTwiceItsRadius) {
    EXPECT_DOUBLE_EQ(defaultBinSize(std::vector<float>(1000, 0.0025f)), 2.0 * 0.0025f);
    EXPECT_EQ(defaultBinSize({}), 0.0);
}

// SMALL-IMPACT's scene: a 10 mm ball over 25,000 grains of 1 mm. Bins of 20 mm would put some 800
// grains in each and test all their pairs; bins of 2 mm hold a few, and the ball spans ~1,700.
TEST(BinGridSizing, ABallAmongSmallGrainsGetsTheGrainsBins) {
    std::vector<float> radii(25000, 0.001f);
    radii.push_back(0.01f);
    EXPECT_DOUBLE_EQ(defaultBinSize(radii), 2.0 * 0.001f);
}

// As many spheres of 10 r as of r: the large ones hold 1,000 times the volume, and bins of 2 r would
// register each of them in 1,331 bins; bins of 20 r are the cheaper.
TEST(BinGridSizing, DominantLargeSpheresGetTheirOwnBins) {
    std::vector<float> radii(500, 0.001f);
    radii.insert(radii.end(), 500, 0.01f);
    EXPECT_DOUBLE_EQ(defaultBinSize(radii), 2.0 * 0.01f);
}

// A continuous size distribution (more than 64 distinct radii) is grouped on a log scale; the edge
// stays within the range of diameters.
TEST(BinGridSizing, ContinuousDistributionStaysInItsRange) {
    std::vector<float> radii;
    for (int i = 0; i < 2000; i++) radii.push_back(0.001f * (1.0f + (float)i / 2000.0f));
    const double size = defaultBinSize(radii);
    EXPECT_GE(size, 2.0 * 0.001f);
    EXPECT_LE(size, 2.0 * 0.002f * 1.0001);
}
