// The GPU's contact-detection kernels (src/backend/cuda/kernels/Detection.cu) checked without a GPU:
// the kernel file is compiled here for the host, each kernel run as a loop over its threads in the
// order CudaKinematics::detect launches them (bin boxes, entries, a stable sort by bin, entries per
// bin summed into bin starts, pair count, offsets, pair fill), and the result compared with the CPU's
// detector (backend/cpu/ContactDetector.h), which is itself checked against brute force: the same
// bin registry and the same contact list, pair for pair and in the same order. The kernels use
// nothing of CUDA but the thread index and one atomic add (tests/HostKernelEmulation.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "DetectionScenes.h"
#include "MeshBuilders.h"
#include "api/SceneAssembly.h"
#include "kinematics/BinGridSizing.h"
#include "dynamics/KinematicCache.h"
#include "backend/cpu/ContactDetector.h"
#include "runtime/FamilyRules.h"

#include "HostKernelEmulation.h"
#include "backend/cuda/kernels/Detection.cu"
#include "HostKernelEmulationEnd.h"

using namespace deme;
using namespace deme_test;

namespace {

void exclusiveSum(std::vector<unsigned int>& v) {
    unsigned int sum = 0;
    for (unsigned int& x : v) {
        const unsigned int c = x;
        x = sum;
        sum += c;
    }
}

// What the kernels leave for one kind of item (spheres or triangles).
struct EmulatedBins {
    std::vector<int> lo, hi;
    std::vector<unsigned int> count, keys, items, sortedKeys, sortedItems, start;
};

// The binning of CudaKinematics::detect, for n items whose boxes `boxes(lo, hi, count)` sets.
template <class Boxes>
void emulateBinning(EmulatedBins& b, unsigned int n, const BinGrid& g, size_t numBins, Boxes&& boxes) {
    b.lo.assign(3 * (size_t)n, 0);
    b.hi.assign(3 * (size_t)n, 0);
    b.count.assign(n + 1, 0);
    boxes();
    exclusiveSum(b.count);  // now the offsets
    const unsigned int entries = b.count[n];
    b.keys.assign(entries, 0);
    b.items.assign(entries, 0);
    runThreads(
        n, [&] { deme_bin_entries(g, n, b.lo.data(), b.hi.data(), b.count.data(), b.keys.data(), b.items.data()); });
    // The radix sort by bin is stable.
    std::vector<unsigned int> order(entries);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](unsigned int x, unsigned int y) { return b.keys[x] < b.keys[y]; });
    b.sortedKeys.resize(entries);
    b.sortedItems.resize(entries);
    for (unsigned int k = 0; k < entries; k++) {
        b.sortedKeys[k] = b.keys[order[k]];
        b.sortedItems[k] = b.items[order[k]];
    }
    b.start.assign(numBins + 1, 0);
    runThreads(entries, [&] { deme_bin_counts(b.keys.data(), entries, b.start.data()); });
    exclusiveSum(b.start);
}

struct EmulatedDetection {
    EmulatedBins spheres, triangles;
    DetectedContacts contacts;
};

EmulatedDetection emulateDetect(SimState& s, const BinGrid& grid, double margin, const uint8_t* mask,
                                const float* extra) {
    StateView v{};
    v.owners.family = s.owners.family.data();
    v.spheres.owner = s.spheres.owner.data();
    v.spheres.radius = s.spheres.radius.data();
    v.analytical.owner = s.analytical.owner.data();
    v.analytical.type = s.analytical.type.data();
    v.analytical.radius = s.analytical.radius.data();
    v.analytical.inside = s.analytical.inside.data();
    v.triangles.owner = s.triangles.owner.data();
    v.cache.spherePos = s.cache.spherePos.data();
    v.cache.analPos = s.cache.analPos.data();
    v.cache.analDir = s.cache.analDir.data();
    v.cache.triVert = s.cache.triVert.data();
    v.numOwners = (uint32_t)s.owners.size();
    v.numSpheres = (uint32_t)s.spheres.size();
    v.numAnalytical = (uint32_t)s.analytical.size();
    v.numTriangles = (uint32_t)s.triangles.size();
    const unsigned int nS = v.numSpheres, nT = v.numTriangles;
    DetectionArgs args{grid, margin, extra, mask, {}, {}, nullptr, nullptr};

    EmulatedDetection r;
    emulateBinning(r.spheres, nS, grid, grid.numBins(), [&] {
        runThreads(nS, [&] {
            deme_sphere_bin_boxes(v, args, r.spheres.lo.data(), r.spheres.hi.data(), r.spheres.count.data());
        });
    });
    std::vector<double3> triLo(nT), triHi(nT);
    emulateBinning(r.triangles, nT, grid, grid.numBins(), [&] {
        runThreads(nT, [&] {
            deme_triangle_bin_boxes(v, args, triLo.data(), triHi.data(), r.triangles.lo.data(), r.triangles.hi.data(),
                                    r.triangles.count.data());
        });
    });
    args.sphereBins =
        BinsView{r.spheres.lo.data(), r.spheres.hi.data(), r.spheres.start.data(), r.spheres.sortedItems.data()};
    if (nT)
        args.triangleBins = BinsView{r.triangles.lo.data(), r.triangles.hi.data(), r.triangles.start.data(),
                                     r.triangles.sortedItems.data()};
    args.triLo = triLo.data();
    args.triHi = triHi.data();
    std::vector<unsigned int> count(nS + 1, 0);
    runThreads(nS, [&] {
        deme_pair_search(v, args, count.data(), (const unsigned int*)nullptr, (bodyID_t*)nullptr, (bodyID_t*)nullptr,
                         (uint8_t*)nullptr);
    });
    std::vector<unsigned int> offset = count;
    exclusiveSum(offset);
    const unsigned int total = offset[nS];
    DetectedContacts& c = r.contacts;
    c.geomA.assign(total, 0);
    c.geomB.assign(total, 0);
    c.type.assign(total, 0);
    runThreads(nS, [&] {
        deme_pair_search(v, args, count.data(), offset.data(), c.geomA.data(), c.geomB.data(), c.type.data());
    });
    return r;
}

// The CPU's registry of the same items (its counting sort), for the bin starts and the entries in
// bin order; the boxes are the shared rule's, with the margin written out here.
BinRegistry cpuSphereBins(const SimState& s, const BinGrid& grid, double margin, const float* extra) {
    BinRegistry reg;
    const size_t n = s.spheres.size();
    reg.resize(n);
    for (size_t i = 0; i < n; i++) {
        const double e = (double)s.spheres.radius[i] + margin + (double)extra[s.owners.family[s.spheres.owner[i]]];
        const double3 p = s.cache.spherePos[i];
        const BinBox b = binBox(grid, make_double3(p.x - e, p.y - e, p.z - e), make_double3(p.x + e, p.y + e, p.z + e));
        storeBinBox(b, i, reg.lo.data(), reg.hi.data());
    }
    reg.build(grid, n);
    return reg;
}

// randomScene with two fixed meshes: a box in the middle (family 2, masked against family 0) and a
// floor (family 1).
Scene sceneWithMeshes(unsigned seed, size_t nClumps) {
    Scene sc = randomScene(seed, nClumps);
    const auto& mat = sc.materials.front();
    auto box = std::make_shared<DEMMeshConnected>(
        boxMesh(make_float3(-0.004f, -0.006f, -0.003f), make_float3(0.005f, 0.004f, 0.006f), mat));
    box->SetFamily(2);
    auto floor = std::make_shared<DEMMeshConnected>(gridFloor(-0.02f, -0.02f, -0.015f, 16, 0.0025f, mat));
    floor->SetFamily(1);
    sc.meshes.push_back(box);
    sc.meshes.push_back(floor);
    return sc;
}

}  // namespace

TEST(CudaDetectionKernels, MatchTheCpuDetectorExactly) {
    const DetectionRules dr;
    const FamilyRules& rules = dr.rules;
    const float* extra = dr.extra;
    int cases = 0;
    for (unsigned seed : {4u, 5u}) {
        const Scene scene = sceneWithMeshes(seed, 1200);
        SimState s = detectionState(scene, "CudaDetectionKernels");
        ASSERT_GT(s.triangles.size(), 500u);
        for (double binSize : {0.0015, 0.004, 0.0}) {
            const BinGrid grid = makeBinGrid(s, binSize);
            for (double margin : {0.0, 1e-4}) {
                SCOPED_TRACE(testing::Message() << "seed " << seed << ", bin " << binSize << ", margin " << margin);
                const EmulatedDetection gpu = emulateDetect(s, grid, margin, rules.contactMask(), extra);
                const BinRegistry cpuBins = cpuSphereBins(s, grid, margin, extra);
                EXPECT_EQ(gpu.spheres.start, cpuBins.start);
                EXPECT_EQ(gpu.spheres.sortedItems, cpuBins.entries);
                ContactDetector det;
                DetectedContacts cpu;
                double binning = 0.0, search = 0.0;
                det.detect(s, grid, margin, rules.contactMask(), extra, cpu, binning, search);
                size_t sphereTriangle = 0;
                for (uint8_t t : cpu.type) sphereTriangle += t == SPHERE_TRIANGLE;
                EXPECT_GT(cpu.size(), 500u);
                EXPECT_GT(sphereTriangle, 20u);
                EXPECT_EQ(gpu.contacts.geomA, cpu.geomA);
                EXPECT_EQ(gpu.contacts.geomB, cpu.geomB);
                EXPECT_EQ(gpu.contacts.type, cpu.type);
                cases++;
            }
        }
    }
    EXPECT_EQ(cases, 12);
}

// The case the bin-count kernel exists for: items in a thin slab of a tall grid, so that long runs
// of bins below and above hold nothing. Every bin's start must still be the first entry at or after
// it, and the last one the number of entries.
TEST(CudaDetectionKernels, BinStartsOfAMostlyEmptyGrid) {
    const BinGrid g{make_double3(0, 0, 0), 1.0, 4, 4, 50};
    const size_t numBins = 4 * 4 * 50;
    // Three unit boxes at z in [20, 22): items 0 and 1 share bins.
    std::vector<int> lo = {0, 0, 20, 1, 1, 20, 3, 3, 21}, hi = {1, 1, 21, 2, 2, 21, 3, 3, 21};
    std::vector<unsigned int> count = {8, 8, 1, 0};
    exclusiveSum(count);
    const unsigned int entries = count[3];
    std::vector<unsigned int> keys(entries), items(entries);
    runThreads(3, [&] { deme_bin_entries(g, 3, lo.data(), hi.data(), count.data(), keys.data(), items.data()); });
    std::vector<unsigned int> start(numBins + 1, 0);
    runThreads(entries, [&] { deme_bin_counts(keys.data(), entries, start.data()); });
    exclusiveSum(start);
    std::vector<unsigned int> sorted = keys;
    std::stable_sort(sorted.begin(), sorted.end());
    for (size_t b = 0; b <= numBins; b++) {
        const unsigned int expected =
            (unsigned int)(std::lower_bound(sorted.begin(), sorted.end(), (unsigned int)b) - sorted.begin());
        ASSERT_EQ(start[b], expected) << "bin " << b;
    }
    EXPECT_EQ(start[numBins], 17u);
    EXPECT_EQ(start[0], 0u);
    // Bin (1, 1, 20) holds items 0 and 1.
    const size_t shared = 1 + 4 * (1 + 4 * 20);
    EXPECT_EQ(start[shared + 1] - start[shared], 2u);
}
