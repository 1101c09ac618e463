// Contact detection with periodic boundaries (physics/Periodic.h): every pair within reach through
// the nearest images, exactly as an O(N^2) minimum-image search finds them, in the contact set's
// (A, B) order; on the CPU's detector and on the GPU's detection kernels run on the host.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "BackendFixture.h"
#include "DetectionScenes.h"
#include "backend/cpu/ContactDetector.h"
#include "kinematics/BinGridSizing.h"

using namespace deme;
using namespace deme_test;

namespace {

std::set<std::pair<bodyID_t, bodyID_t>> pairsOf(const DetectedContacts& found) {
    std::set<std::pair<bodyID_t, bodyID_t>> got;
    for (size_t i = 0; i < found.size(); i++) {
        if (i > 0) EXPECT_LT(contactKey(found.geomA[i - 1], found.geomB[i - 1]), contactKey(found.geomA[i], found.geomB[i]));
        got.insert({found.geomA[i], found.geomB[i]});
    }
    return got;
}

}  // namespace

TEST(PeriodicDetection, MatchesTheMinimumImageBruteForceExactly) {
    const DetectionRules dr;
    int cases = 0;
    for (unsigned int axes : {1u, 3u, 7u, 5u}) {
        const Scene scene = randomPeriodicScene(7 + axes, 1500, axes);
        SimState s = detectionState(scene, "PeriodicDetection");
        ASSERT_EQ(s.frame.periodic.axes, axes);
        // Bins smaller than the largest spheres (boxes over several bins and over faces), bins that
        // do not divide the period (widened to tile it), and the default.
        for (double binSize : {0.0015, 0.0037, 0.0}) {
            const BinGrid grid = makeBinGrid(s, binSize);
            for (double margin : {0.0, 2e-4}) {
                ContactDetector det;
                DetectedContacts found;
                double binning = 0.0, search = 0.0;
                det.detect(s, grid, margin, dr.rules.contactMask(), dr.extra, found, binning, search);
                const auto expected = bruteForce(s, margin, dr.rules.contactMask(), dr.extra);
                // The pairs across faces are there, and they are many.
                size_t across = 0;
                for (const auto& [a, b] : expected) {
                    if (b >= s.spheres.size()) continue;
                    const double3 d = s.cache.spherePos[a] - s.cache.spherePos[b];
                    across += (std::fabs(d.x) > 0.02 || std::fabs(d.y) > 0.02 || std::fabs(d.z) > 0.02) ? 1 : 0;
                }
                EXPECT_GT(across, 50u) << "axes " << axes;
                EXPECT_EQ(pairsOf(found), expected) << "axes " << axes << ", bin " << binSize << ", margin " << margin;
                cases++;
            }
        }
    }
    EXPECT_EQ(cases, 24);
}

// Spheres by centre in a periodic cell of two and three bins a side: the search box of a sphere
// then spans a whole period along some axes, whose bins are searched once each (withinOnePeriod),
// and every pair through the nearest images is found once, as by boxes (DEME_BIN_BY_BOXES=1).
TEST(PeriodicDetection, SpheresByCentreInACellOfFewBins) {
    const DetectionRules dr;
    int cases = 0;
    for (unsigned int axes : {7u, 3u}) {
        const Scene scene = randomPeriodicScene(31 + axes, 1500, axes);
        SimState s = detectionState(scene, "PeriodicDetection");
        const float largest = *std::max_element(s.spheres.radius.begin(), s.spheres.radius.end());
        for (double binSize : {0.02, 0.0133}) {
            const BinGrid grid = makeBinGrid(s, binSize);
            const double margin = 2e-4;
            ASSERT_GT(centreReachFor(grid, margin, dr.extra, largest), 0.0) << "bin " << binSize;
            const auto expected = bruteForce(s, margin, dr.rules.contactMask(), dr.extra);
            for (const char* byBoxes : {"0", "1"}) {
                const ScopedEnvironmentVariable registration("DEME_BIN_BY_BOXES", byBoxes);
                ContactDetector det;
                DetectedContacts found;
                double binning = 0.0, search = 0.0;
                det.detect(s, grid, margin, dr.rules.contactMask(), dr.extra, found, binning, search);
                EXPECT_EQ(pairsOf(found), expected)
                    << "axes " << axes << ", bin " << binSize << ", by boxes " << byBoxes;
                EXPECT_EQ(pairsOf(found).size(), found.size())
                    << "a pair reported twice: axes " << axes << ", bin " << binSize << ", by boxes " << byBoxes;
                cases++;
            }
        }
    }
    EXPECT_EQ(cases, 8);
}

// A sheared cell (Lees–Edwards): the images across the z faces are displaced along x by the offset;
// detection finds exactly the pairs of a brute-force search through those images, at offsets of a
// fraction of a bin, of several bins and of nearly half the period, and the pairs across the z faces
// at such an offset are many.
TEST(PeriodicDetection, ShearedCellMatchesTheBruteForceThroughDisplacedImages) {
    const DetectionRules dr;
    int cases = 0;
    for (unsigned int axes : {5u, 7u}) {
        Scene scene = randomPeriodicScene(11 + axes, 1500, axes);
        scene.sheared = true;
        scene.shearRate = 2.0;
        SimState s = detectionState(scene, "PeriodicDetection");
        ASSERT_EQ(s.frame.periodic.shear, 1u);
        ASSERT_DOUBLE_EQ(s.frame.periodic.shearVelocity, 2.0 * s.frame.periodic.length.z);
        for (double fraction : {0.013, 0.31, -0.4999}) {
            // The offset rate * Lz * t is this fraction of the period.
            s.frame.periodic.shearTime = fraction * s.frame.periodic.length.x / s.frame.periodic.shearVelocity;
            for (double binSize : {0.0015, 0.0037, 0.0}) {
                const BinGrid grid = makeBinGrid(s, binSize);
                EXPECT_EQ(grid.shear, 1u);
                ContactDetector det;
                DetectedContacts found;
                double binning = 0.0, search = 0.0;
                det.detect(s, grid, 2e-4, dr.rules.contactMask(), dr.extra, found, binning, search);
                const auto expected = bruteForce(s, 2e-4, dr.rules.contactMask(), dr.extra);
                size_t acrossZ = 0;
                for (const auto& [a, b] : expected)
                    acrossZ += b < s.spheres.size() &&
                               std::fabs(s.cache.spherePos[a].z - s.cache.spherePos[b].z) > 0.02;
                EXPECT_GT(acrossZ, 30u);
                EXPECT_EQ(pairsOf(found), expected)
                    << "axes " << axes << ", offset " << fraction << " Lx, bin " << binSize;
                cases++;
            }
        }
    }
    EXPECT_EQ(cases, 18);
}

// A periodic axis gets whole bins over its period, each at least the size asked for.
TEST(PeriodicDetection, BinsTileThePeriod) {
    const Scene scene = randomPeriodicScene(3, 200, 5u);
    const SimState s = detectionState(scene, "PeriodicDetection");
    const BinGrid g = makeBinGrid(s, 0.0037);
    EXPECT_EQ(g.periodic, 5u);
    EXPECT_EQ(g.nx, 10);  // floor(0.04 / 0.0037)
    EXPECT_NEAR(g.edge.x * g.nx, s.domainSize.x, 1e-15);
    EXPECT_GE(g.edge.x, 0.0037);
    EXPECT_EQ(g.ny, 11);  // bounded: ceil(0.04 / 0.0037), edges of the size asked for
    EXPECT_EQ(g.edge.y, 0.0037);
    // Coordinates one bin past either face wrap to the bins at the other face.
    EXPECT_EQ(binIndex(g, -1, 0, 0), binIndex(g, 9, 0, 0));
    EXPECT_EQ(binIndex(g, 10, 0, 0), binIndex(g, 0, 0, 0));
    EXPECT_EQ(binIndex(g, 0, 0, -1), binIndex(g, 0, 0, g.nz - 1));
}
