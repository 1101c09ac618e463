// The plan of a detection in slabs of bin layers (kinematics/BinSlabs.h): the slabs search every
// layer once, bin their layers and a halo that holds every partner and every bin a search walks, and
// are made only where the whole grid's bins would pass the bound. (The kernels' slabs are checked
// against the CPU detector in CudaDetectionKernels.SlabsFindTheCpuDetectorsPairs.)
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include <deme/Error.h>

#include "BackendFixture.h"
#include "runtime/DetectionSlabs.h"
#include "kinematics/DetectionRules.h"

using namespace deme;
using namespace deme_test;

namespace {

BinGrid grid(int nx, int ny, int nz, double edge) {
    return BinGrid{make_double3(0, 0, 0), edge, make_double3(edge, edge, edge), nx, ny, nz, 0u, 0u, 0.0};
}

}  // namespace

// Every layer is searched by exactly one slab; a slab bins its searched layers and `halo` more
// either side, cut to the grid; its first bin is its first binned layer's.
TEST(BinSlabs, SlabsSearchEveryLayerOnceAndBinTheirHalo) {
    const BinGrid g = grid(7, 5, 23, 1.0);
    for (int slabs : {1, 2, 3, 5, 23})
        for (int halo : {1, 2}) {
            std::vector<int> searchedBy(g.nz, 0);
            for (int k = 0; k < slabs; k++) {
                const BinSlab s = binSlab(g, halo, slabs, k);
                ASSERT_LT(s.searched.from, s.searched.to);
                for (int z = s.searched.from; z < s.searched.to; z++) searchedBy[z]++;
                EXPECT_EQ(s.binned.from, std::max(0, s.searched.from - halo));
                EXPECT_EQ(s.binned.to, std::min(g.nz, s.searched.to + halo));
                EXPECT_EQ(s.firstBin(g), binIndex(g, 0, 0, s.binned.from));
                EXPECT_EQ(s.numBins(g), (uint64_t)7 * 5 * (s.binned.to - s.binned.from));
            }
            for (int z = 0; z < g.nz; z++) EXPECT_EQ(searchedBy[z], 1) << slabs << " slabs, layer " << z;
        }
    const BinSlab whole = wholeGridSlab(g);
    EXPECT_TRUE(isWholeGrid(g, whole.searched));
    EXPECT_EQ(whole.numBins(g), g.numBins());
    EXPECT_EQ(whole.firstBin(g), 0u);
}

// The halo holds every partner: two centres less than 2 centreReach apart along z lie at most `halo`
// layers apart by binCoord, and a search box (a centre +- 2 centreReach, searchedSphere) spans at
// most `halo` layers either side of its centre's, for random centres, edges and reaches, on layer
// boundaries too.
TEST(BinSlabs, HaloHoldsEveryPartnerAndEverySearchedBin) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    EXPECT_EQ(slabHalo(grid(4, 4, 40, 1.0), 0.4), 1);
    EXPECT_EQ(slabHalo(grid(4, 4, 40, 1.0), 0.75), 2);
    for (int trial = 0; trial < 20000; trial++) {
        const double edge = 0.001 + 0.01 * u(rng);
        const BinGrid g = grid(4, 4, 400, edge);
        const double reach = 0.75 * edge * (0.05 + 0.95 * u(rng));  // centreReachFor's range
        const int halo = slabHalo(g, reach);
        // A centre inside the grid, half of them on a layer boundary.
        const int layer = 1 + (int)(u(rng) * 390);
        const double z = trial % 2 ? g.origin.z + layer * edge : g.origin.z + (layer + u(rng)) * edge;
        const double d = 2.0 * reach * (trial % 3 ? u(rng) : 0.999999999);
        const int zA = binCoord(g, 2, z);
        for (double zB : {z - d, z + d}) EXPECT_LE(std::abs(binCoord(g, 2, zB) - zA), halo) << trial;
        const double3 c = make_double3(0.5 * edge, 0.5 * edge, z);
        const double h = 2.0 * reach;
        const BinBox box = binBox(g, c - make_double3(h, h, h), c + make_double3(h, h, h));
        EXPECT_GE(box.lo[2], zA - halo) << trial;
        EXPECT_LE(box.hi[2], zA + halo) << trial;
    }
}

// One slab where slabs are not possible (no binning by centres, a periodic z, a sheared cell), the
// whole grid's bins stay under the bound (32 MiB, or 4 B a searched sphere) or the device has room
// for them; otherwise the fewest slabs that fit the device, at most the whole grid's bins over the
// bound and a slab per four halos of layers (so many where nothing fits, and for the estimate).
// DEME_DETECTION_SLABS asks for a number (at most a layer each), and anything but digits is an error naming it.
TEST(BinSlabs, SlabCountFollowsTheBoundAndTheGrid) {
    ScopedEnvironmentVariable unset("DEME_DETECTION_SLABS", "");
    const double reach = 0.7;                // halo 2
    BinGrid g = grid(1000, 1000, 400, 1.0);  // 4e8 bins: 1.6 GB of starts a kind
    const double spheres = 5.1e7;            // bound 204 MB
    EXPECT_EQ(detectionSlabCount(g, 0.0, 1, spheres, spheres), 1);
    const int slabs = detectionSlabCount(g, reach, 1, spheres, spheres);
    EXPECT_EQ(slabs, (int)std::ceil((4.0 * (4e8 + 2) + 4.0 * spheres) / (4.0 * spheres)));  // 9
    EXPECT_EQ(detectionSlabCount(g, reach, 2, spheres, spheres), 17);
    // Where the device has room for the whole grid's bins beside the offsets and pairs (within 9/10
    // of its free memory): one slab; where it has room for two slabs' thickest: two.
    const double whole = 4.0 * (4e8 + 2) + 4.0 * spheres, besides = 2e9;
    EXPECT_EQ(detectionSlabCount(g, reach, 1, spheres, spheres, besides, (whole + besides) / 0.9 * 1.001), 1);
    EXPECT_EQ(detectionSlabCount(g, reach, 1, spheres, spheres, besides, (whole + besides) / 0.9 * 0.999), 2);
    // The fewest slabs whose thickest fits: 3 where 2 do not, the bound's 9 where none of fewer does.
    const double two = slabBinBytes(g, reach, 2, 1, spheres), three = slabBinBytes(g, reach, 3, 1, spheres);
    ASSERT_LT(three, two);
    EXPECT_EQ(detectionSlabCount(g, reach, 1, spheres, spheres, besides, (two + besides) / 0.9 * 0.999), 3);
    EXPECT_EQ(detectionSlabCount(g, reach, 1, spheres, spheres, besides, (three + besides) / 0.9 * 1.001), 3);
    EXPECT_EQ(detectionSlabCount(g, reach, 1, spheres, spheres, besides, besides), 9);
    EXPECT_LT(slabBinBytes(g, reach, slabs, 1, spheres), slabBinBytes(g, reach, 1, 1, spheres) / 6.0);
    // Few layers: at most nz / (4 halo) slabs.
    BinGrid flat = grid(20000, 20000, 40, 1.0);
    EXPECT_EQ(detectionSlabCount(flat, reach, 1, spheres, spheres), 5);
    // Small: one slab.
    EXPECT_EQ(detectionSlabCount(grid(100, 100, 100, 1.0), reach, 2, 1e6, 1e6), 1);
    BinGrid periodicZ = g;
    periodicZ.periodic = 4u;
    EXPECT_EQ(detectionSlabCount(periodicZ, reach, 1, spheres, spheres), 1);
    BinGrid periodicXY = g;
    periodicXY.periodic = 3u;
    EXPECT_EQ(detectionSlabCount(periodicXY, reach, 1, spheres, spheres), 9);
    BinGrid sheared = g;
    sheared.shear = 1u;
    EXPECT_EQ(detectionSlabCount(sheared, reach, 1, spheres, spheres), 1);
    {
        ScopedEnvironmentVariable asked("DEME_DETECTION_SLABS", "3");
        EXPECT_EQ(detectionSlabCount(grid(10, 10, 10, 1.0), reach, 1, 10, 10), 3);
        EXPECT_EQ(detectionSlabCount(periodicZ, reach, 1, spheres, spheres), 1);
    }
    {
        ScopedEnvironmentVariable asked("DEME_DETECTION_SLABS", "500");
        EXPECT_EQ(detectionSlabCount(grid(10, 10, 10, 1.0), reach, 1, 10, 10), 10);
    }
    for (const char* bad : {"x", "-2", "3 slabs"}) {
        ScopedEnvironmentVariable asked("DEME_DETECTION_SLABS", bad);
        try {
            detectionSlabCount(g, reach, 1, spheres, spheres);
            ADD_FAILURE() << "no error for " << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("DEME_DETECTION_SLABS"), std::string::npos) << e.what();
        }
    }
}
