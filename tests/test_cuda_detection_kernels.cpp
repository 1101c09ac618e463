// The GPU's contact-detection kernels (src/backend/cuda/kernels/Detection.cu) checked without a GPU:
// the kernel file is compiled here for the host, each kernel run as a loop over its threads in the
// order CudaKinematics::detect launches them (bin counts from each item's box, their sum into bin
// starts, the entries scattered and sorted per bin, pair count, offsets, pair fill), and the result compared with the CPU's
// detector (backend/cpu/ContactDetector.h), which is itself checked against brute force: the same
// bin registry and the same contact list, pair for pair and in the same order. The kernels use
// nothing of CUDA but the thread index and one atomic add (tests/HostKernelEmulation.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

#include "DetectionScenes.h"
#include "MeshBuilders.h"
#include "api/SceneAssembly.h"
#include "state/ContactTypeOf.h"
#include "kinematics/BinGridSizing.h"
#include "dynamics/KinematicCache.h"
#include "backend/cpu/ContactDetector.h"
#include "kinematics/DormantRules.h"
#include "runtime/DetectionSlabs.h"
#include "runtime/FamilyRules.h"

#include "BackendFixture.h"
#include "backend/cuda/DetectionLanes.h"

#include "HostKernelEmulation.h"
#include "backend/cuda/kernels/Detection.cu"
#include "EmulatedPairA.h"
#include "HostKernelEmulationEnd.h"

using namespace deme;
using namespace deme_test;

namespace {

template <class T>
void exclusiveSum(std::vector<T>& v) {
    T sum = 0;
    for (T& x : v) {
        const T c = x;
        x = sum;
        sum += c;
    }
}

// A stable sort of (key, item) pairs by key, as CUB's radix sort.
template <class Key>
void stableSortPairs(const std::vector<Key>& keys, const std::vector<unsigned int>& items, std::vector<Key>& sortedKeys,
                     std::vector<unsigned int>& sortedItems) {
    std::vector<unsigned int> order(keys.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](unsigned int x, unsigned int y) { return keys[x] < keys[y]; });
    sortedKeys.resize(keys.size());
    sortedItems.resize(keys.size());
    for (size_t k = 0; k < keys.size(); k++) {
        sortedKeys[k] = keys[order[k]];
        sortedItems[k] = items[order[k]];
    }
}

// What the kernels leave for one kind of item (spheres or triangles): start has numBins + 2 entries
// (the first numBins + 1 are each bin's first entry and the end).
struct EmulatedBins {
    std::vector<unsigned int> start, items;
    std::vector<unsigned int> starts(size_t numBins) const { return {start.begin(), start.begin() + numBins + 1}; }
};

// The counting sort of CudaKinematics::detect, for items ids[0, n) (all of them if null) of a kind,
// whose boxes the kernels compute from `v` and `args`. The scatter's threads run from the last to the
// first: on a GPU their order is the atomics', and the per-bin sort must put each bin's items in
// increasing order whatever it was.
// `lanes` threads an item, as CudaKinematics::detect launches them (DetectionLanes.h).
// In slabs (kinematics/BinSlabs.h) the bins of the layers `layers` only, numBins of them.
void emulateBinning(EmulatedBins& b, const StateView& v, const DetectionArgs& args, BinnedKind kind,
                    const bodyID_t* ids, unsigned int n, size_t numBins, unsigned int lanes = 1,
                    LayerRange layers = LayerRange{0, std::numeric_limits<int>::max()}) {
    b.start.assign(numBins + 2, 0);
    runThreads((size_t)n * lanes, [&] { deme_bin_count(v, args, kind, ids, n, lanes, layers, b.start.data()); });
    exclusiveSum(b.start);
    b.items.assign(b.start[numBins + 1], 0);
    runThreadsReversed((size_t)n * lanes,
                       [&] { deme_bin_scatter(v, args, kind, ids, n, lanes, layers, b.start.data(), b.items.data()); });
    runThreads(numBins, [&] { deme_bin_sort(b.start.data(), numBins, b.items.data()); });
}

// The dormant registry as DeviceDormantRegistry::rebuild builds it.
struct EmulatedRegistry {
    std::vector<bodyID_t> moving;
    std::vector<unsigned int> start, sortedItems;
    double maxReach = 0.0;
    bool blocked = false;  // a movable wall or mesh reaches a dormant family: full search
};

EmulatedRegistry emulateRegistry(const StateView& v, const BinGrid& grid, const uint8_t* dormant,
                                 const uint8_t* movable, const uint8_t* mask, const float* extra) {
    EmulatedRegistry r;
    const unsigned int nS = v.numSpheres;
    unsigned int flags[2] = {0u, 0u};
    runThreads(v.numOwners, [&] { deme_dormant_check(v, v.owners.family, movable, dormant, mask, flags); });
    EXPECT_EQ(flags[0], 0u);  // checked against the families themselves
    r.blocked = flags[1] != 0;
    std::vector<unsigned int> isMoving(nS + 1, 0), isDormant(nS + 1, 0);
    std::vector<double> reach(nS, 0.0);
    runThreads(nS, [&] { deme_dormant_flags(v, dormant, extra, isMoving.data(), isDormant.data(), reach.data()); });
    for (double x : reach) r.maxReach = std::max(r.maxReach, x);
    exclusiveSum(isMoving);  // now the offsets
    exclusiveSum(isDormant);
    r.moving.assign(isMoving[nS], 0);
    std::vector<unsigned int> keys(isDormant[nS]), items(isDormant[nS]), sortedKeys;
    runThreads(nS, [&] {
        deme_dormant_scatter(v, grid, dormant, isMoving.data(), isDormant.data(), r.moving.data(), keys.data(),
                             items.data());
    });
    stableSortPairs(keys, items, sortedKeys, r.sortedItems);
    r.start.assign(grid.numBins() + 1, 0);
    runThreads(keys.size(), [&] { deme_bin_counts(keys.data(), (unsigned int)keys.size(), r.start.data()); });
    exclusiveSum(r.start);
    return r;
}

struct EmulatedDetection {
    EmulatedBins spheres, triangles;
    EmulatedRegistry registry;
    bool usedRegistry = false;
    DetectedContacts contacts;
};

// The state as the detection kernels read it (CudaKinematics::detect's view, positions from the
// cache).
StateView detectionView(SimState& s) {
    StateView v{};
    v.frame = s.frame;  // periodic axes, if any
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
    return v;
}

// How CudaKinematics::detect spreads the spheres' work over threads (DetectionLanes.h): threads an
// item in registration; the radius from which a sphere is wide, and the threads a wide sphere's
// search takes; threads a sphere in the search of the others. The default is a thread an item.
struct Spread {
    unsigned int binLanes = 1;
    float wideRadius = std::numeric_limits<float>::infinity();
    unsigned int wideLanes = cuda::WIDE_SPHERE_LANES;
    unsigned int searchLanes = 1;
};

// CudaKinematics::detect; with `dormant` (1 per dormant family) and `movable` (1 per owner that
// can move) as DeviceDormantRegistry::prepare, without them a full search; spread as `spread` says
// (but a thread a sphere with the registry, as on the GPU).
EmulatedDetection emulateDetect(SimState& s, const BinGrid& sceneGrid, double margin, const uint8_t* mask,
                                const float* extra, const uint8_t* dormant = nullptr, const uint8_t* movable = nullptr,
                                Spread spread = Spread{}) {
    // A sheared cell's image layers displaced by the state's offset, as CudaKinematics::detect.
    const BinGrid grid = withShearOffset(sceneGrid, s.frame.periodic);
    const StateView v = detectionView(s);
    const unsigned int nS = v.numSpheres, nT = v.numTriangles;
    DetectionArgs args{grid, margin, extra, mask, {}, {}, nullptr, nullptr, sharedExtraMarginOf(extra)};
    // Spheres by centre wherever the rule allows, whatever the scene's size (CudaKinematics::detect
    // does so from DETECTION_LANES_BELOW spheres, centreBinning): the kernels are checked in both
    // registrations, each test's bin sizes deciding between them.
    const float largest = nS ? *std::max_element(s.spheres.radius.begin(), s.spheres.radius.end()) : 0.f;
    args.centreReach = centreReachFor(grid, margin, extra, (double)largest);

    EmulatedDetection r;
    DormantBinsView dormantBins{nullptr, nullptr, 0.0};
    if (dormant) {
        r.registry = emulateRegistry(v, grid, dormant, movable, mask, extra);
        r.usedRegistry = !r.registry.blocked && !r.registry.sortedItems.empty();
        if (r.usedRegistry)
            dormantBins = DormantBinsView{r.registry.start.data(), r.registry.sortedItems.data(), r.registry.maxReach};
    }
    const bodyID_t* ids = r.usedRegistry ? r.registry.moving.data() : nullptr;
    const unsigned int nSearched = r.usedRegistry ? (unsigned int)r.registry.moving.size() : nS;
    if (r.usedRegistry) spread = Spread{};
    const unsigned int lanes = spread.wideLanes;
    std::vector<bodyID_t> wide;  // as CudaKinematics::setGeometry lists them
    for (size_t i = 0; i < nS; i++)
        if (s.spheres.radius[i] >= spread.wideRadius) wide.push_back((bodyID_t)i);
    const unsigned int nWide = (unsigned int)wide.size();
    emulateBinning(r.spheres, v, args, BINNED_SPHERES, ids, nSearched, grid.numBins(), spread.binLanes);
    std::vector<double3> triLo(nT), triHi(nT);
    args.triLo = triLo.data();
    args.triHi = triHi.data();
    runThreads(nT, [&] { deme_triangle_boxes(v, args, triLo.data(), triHi.data()); });
    emulateBinning(r.triangles, v, args, BINNED_TRIANGLES, nullptr, nT, grid.numBins());
    args.sphereBins = BinsView{r.spheres.start.data(), r.spheres.items.data()};
    if (nT) args.triangleBins = BinsView{r.triangles.start.data(), r.triangles.items.data()};
    // As on the GPU: counts, then their exclusive sum in place.
    std::vector<PairOffset> offset(nSearched + 1, 0);
    const unsigned int sLanes = spread.searchLanes;
    if (sLanes > 1)
        runThreads((size_t)nSearched * sLanes, [&] {
            deme_pair_search_lanes(v, args, nSearched, sLanes, spread.wideRadius, offset.data(),
                                   (const PairOffset*)nullptr, (unsigned int*)nullptr, (bodyID_t*)nullptr);
        });
    else
        runThreads(nSearched, [&] {
            deme_pair_search(v, args, dormantBins, ids, nSearched, spread.wideRadius, wholeGridSlab(grid).searched,
                             offset.data(), (const PairOffset*)nullptr, (bodyID_t*)nullptr, (bodyID_t*)nullptr);
        });
    runThreads((size_t)nWide * lanes, [&] {
        deme_pair_search_wide(v, args, wide.data(), nWide, lanes, offset.data(), (const PairOffset*)nullptr,
                              (unsigned int*)nullptr, (bodyID_t*)nullptr);
    });
    exclusiveSum(offset);
    const size_t total = offset[nSearched];
    // A one thread a sphere search without the registry leaves A to the offsets (CudaKinematics).
    const bool aFromOffsets = !r.usedRegistry && sLanes == 1 && nWide == 0;
    DetectedContacts& c = r.contacts;
    c.geomA.assign(total, 0);
    c.geomB.assign(total, 0);
    if (sLanes > 1) {
        // Backwards: a sphere's lanes write its partners in the order of their atomics, which
        // deme_pair_order must undo whatever it was.
        std::vector<unsigned int> cursor(nSearched, 0);
        runThreadsReversed((size_t)nSearched * sLanes, [&] {
            deme_pair_search_lanes(v, args, nSearched, sLanes, spread.wideRadius, (PairOffset*)nullptr, offset.data(),
                                   cursor.data(), c.geomB.data());
        });
        runThreads(nSearched, [&] {
            deme_pair_order(v, nSearched, spread.wideRadius, offset.data(), c.geomA.data(), c.geomB.data());
        });
    } else {
        runThreads(nSearched, [&] {
            deme_pair_search(v, args, dormantBins, ids, nSearched, spread.wideRadius, wholeGridSlab(grid).searched,
                             (PairOffset*)nullptr, offset.data(), aFromOffsets ? nullptr : c.geomA.data(),
                             c.geomB.data());
        });
    }
    if (nWide) {
        // Backwards: a wide sphere's lanes write its partners in the order of their atomics, which
        // the ranking must undo whatever it was.
        std::vector<unsigned int> cursor(nWide, 0);
        runThreadsReversed((size_t)nWide * lanes, [&] {
            deme_pair_search_wide(v, args, wide.data(), nWide, lanes, (PairOffset*)nullptr, offset.data(),
                                  cursor.data(), c.geomB.data());
        });
        for (unsigned int w = 0; w < nWide; w++) EXPECT_EQ(cursor[w], offset[wide[w] + 1] - offset[wide[w]]);
        runThreads((size_t)nWide * lanes, [&] {
            deme_pair_rank_wide(wide.data(), nWide, lanes, offset.data(), c.geomA.data(), c.geomB.data());
        });
        runThreads((size_t)nWide * lanes, [&] {
            deme_pair_finish_wide(wide.data(), nWide, lanes, offset.data(), c.geomA.data(), c.geomB.data());
        });
    }
    if (r.usedRegistry) {  // DeviceDormantRegistry::sortPairs
        std::vector<unsigned long long> keys(total), sortedKeys;
        std::vector<unsigned int> idx(total), sortedIdx;
        // As DeviceDormantRegistry::sortPairs: B's bits cover every geometry id.
        int bBits = 1;
        while ((1ull << bBits) <= (unsigned long long)v.triangleIdBase() + v.numTriangles) bBits++;
        runThreads(total,
                   [&] { deme_pair_keys(c.geomA.data(), c.geomB.data(), total, bBits, keys.data(), idx.data()); });
        stableSortPairs(keys, idx, sortedKeys, sortedIdx);
        runThreads(total,
                   [&] { deme_pairs_from_keys(sortedKeys.data(), total, bBits, c.geomA.data(), c.geomB.data()); });
    }
    // The As compact, as the GPU makes them (kernels/PairAKernels.cuh): from the offsets, or from the
    // whole ones written above; read back whole.
    const HostCompactPairAs compact =
        compactPairAsByKernels(aFromOffsets ? nullptr : c.geomA.data(), offset.data(), nSearched, total);
    expandPairAs(compact.list(), total, c.geomA.data());
    return r;
}

// CudaKinematics::detect in `slabs` slabs of bin layers (kinematics/BinSlabs.h; spheres by their
// centres, a thread an item, no registry): each slab's bins made, its spheres' partners counted; the
// offsets; from the last slab (whose bins are held) to the first, each slab's bins made again and
// its spheres' partners filled. Also the largest slab's bins (starts and entries, spheres' and
// triangles'), in 4-byte words.
struct SlabDetection {
    DetectedContacts contacts;
    size_t largestBinWords = 0;
};
SlabDetection emulateDetectInSlabs(SimState& s, const BinGrid& grid, double margin, const uint8_t* mask,
                                   const float* extra, int slabs) {
    const StateView v = detectionView(s);
    const unsigned int nS = v.numSpheres, nT = v.numTriangles;
    DetectionArgs args{grid, margin, extra, mask, {}, {}, nullptr, nullptr, sharedExtraMarginOf(extra)};
    const float largest = *std::max_element(s.spheres.radius.begin(), s.spheres.radius.end());
    args.centreReach = centreReachFor(grid, margin, extra, (double)largest);
    EXPECT_TRUE(slabsPossible(grid, args.centreReach));
    const int halo = slabHalo(grid, args.centreReach);
    std::vector<double3> triLo(nT), triHi(nT);
    args.triLo = triLo.data();
    args.triHi = triHi.data();
    runThreads(nT, [&] { deme_triangle_boxes(v, args, triLo.data(), triHi.data()); });
    EmulatedBins spheres, triangles;
    SlabDetection r;
    auto binSlab_ = [&](const BinSlab& slab) {
        const size_t n = slab.numBins(grid);
        emulateBinning(spheres, v, args, BINNED_SPHERES, nullptr, nS, n, 1u, slab.binned);
        emulateBinning(triangles, v, args, BINNED_TRIANGLES, nullptr, nT, n, 1u, slab.binned);
        args.sphereBins = BinsView{spheres.start.data(), spheres.items.data(), slab.firstBin(grid)};
        args.triangleBins = BinsView{triangles.start.data(), triangles.items.data(), slab.firstBin(grid)};
        r.largestBinWords = std::max(r.largestBinWords, spheres.start.size() + spheres.items.size() +
                                                            triangles.start.size() + triangles.items.size());
    };
    const DormantBinsView none{nullptr, nullptr, 0.0};
    const float noWide = std::numeric_limits<float>::infinity();
    std::vector<PairOffset> offset(nS + 1, 0);
    for (int k = 0; k < slabs; k++) {
        const BinSlab slab = binSlab(grid, halo, slabs, k);
        binSlab_(slab);
        runThreads(nS, [&] {
            deme_pair_search(v, args, none, nullptr, nS, noWide, slab.searched, offset.data(),
                             (const PairOffset*)nullptr, (bodyID_t*)nullptr, (bodyID_t*)nullptr);
        });
    }
    exclusiveSum(offset);
    DetectedContacts& c = r.contacts;
    c.geomA.assign(offset[nS], 0);
    c.geomB.assign(offset[nS], 0);
    for (int k = slabs - 1; k >= 0; k--) {  // the last slab's bins still held from the count
        const BinSlab slab = binSlab(grid, halo, slabs, k);
        if (k < slabs - 1) binSlab_(slab);
        runThreads(nS, [&] {
            deme_pair_search(v, args, none, nullptr, nS, noWide, slab.searched, (PairOffset*)nullptr, offset.data(),
                             (bodyID_t*)nullptr, c.geomB.data());
        });
    }
    // A from the offsets, in the compact form, as the GPU makes it (kernels/PairAKernels.cuh).
    expandPairAs(compactPairAsByKernels(nullptr, offset.data(), nS, c.geomB.size()).list(), c.geomB.size(),
                 c.geomA.data());
    return r;
}

// The CPU's registry of the same items (its counting sort), for the bin starts and the entries in
// bin order; the boxes are the shared rule's, with the margin written out here (by centre, each
// sphere's centre's bin, where the CPU's detector registers so).
BinRegistry cpuSphereBins(const SimState& s, const BinGrid& grid, double margin, const float* extra) {
    const float largest = *std::max_element(s.spheres.radius.begin(), s.spheres.radius.end());
    const bool byCentre = centreReachFor(grid, margin, extra, (double)largest) > 0.0;
    BinRegistry reg;
    reg.build(grid, nullptr, s.spheres.size(), [&](size_t i) {
        const double3 p = s.cache.spherePos[i];
        if (byCentre) return pointBin(grid, p);
        const double e = (double)s.spheres.radius[i] + margin + (double)extra[s.owners.family[s.spheres.owner[i]]];
        return binBox(grid, make_double3(p.x - e, p.y - e, p.z - e), make_double3(p.x + e, p.y + e, p.z + e));
    });
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

// The emulated kernels' contact list against the CPU detector's, pair for pair, on a scene with
// many sphere-triangle pairs.
// The kernels' contact list is the CPU's, pair for pair, on a list of over 500 pairs with more than
// `minSphereTriangle` sphere-triangle pairs.
static void expectSameList(const SimState& s, const DetectedContacts& gpu, const DetectedContacts& cpu,
                           size_t minSphereTriangle) {
    size_t sphereTriangle = 0;
    for (bodyID_t b : cpu.geomB) sphereTriangle += contactTypeOf(s, b) == SPHERE_TRIANGLE;
    EXPECT_GT(cpu.size(), 500u);
    EXPECT_GT(sphereTriangle, minSphereTriangle);
    EXPECT_EQ(gpu.geomA, cpu.geomA);
    EXPECT_EQ(gpu.geomB, cpu.geomB);
}

// Spreads for the scenes of randomScene (radii 0.3-2 mm): a thread an item; 3 threads an item
// (splitting most boxes' rows unevenly) and the spheres from 1.2 mm wide with 3 lanes; 16 threads
// an item (most rows a thread of their own, lanes left idle) and the spheres from 0.8 mm wide with
// a warp each; 2 threads a sphere in the search and none wide.
static const Spread SPREADS[] = {Spread{}, Spread{3u, 0.0012f, 3u, 3u}, Spread{16u, 0.0008f, 32u, 16u},
                                 Spread{1u, std::numeric_limits<float>::infinity(), 32u, 2u}};

// The emulated kernels against the CPU detector, in every spread.
static void expectTheCpuDetectorsPairs(SimState& s, const BinGrid& grid, double margin, const DetectionRules& dr) {
    ContactDetector det;
    DetectedContacts cpu;
    double binning = 0.0, search = 0.0;
    det.detect(s, grid, margin, dr.rules.contactMask(), dr.extra, cpu, binning, search);
    for (const Spread& spread : SPREADS) {
        SCOPED_TRACE(testing::Message() << spread.binLanes << " threads an item, wide from " << spread.wideRadius);
        const EmulatedDetection gpu =
            emulateDetect(s, grid, margin, dr.rules.contactMask(), dr.extra, nullptr, nullptr, spread);
        expectSameList(s, gpu.contacts, cpu, 20);
    }
}

TEST(CudaDetectionKernels, MatchTheCpuDetectorExactly) {
    const DetectionRules dr;
    int cases = 0;
    for (unsigned seed : {4u, 5u}) {
        const Scene scene = sceneWithMeshes(seed, 1200);
        SimState s = detectionState(scene, "CudaDetectionKernels");
        ASSERT_GT(s.triangles.size(), 500u);
        for (double binSize : {0.0015, 0.004, 0.0}) {
            const BinGrid grid = makeBinGrid(s, binSize);
            for (double margin : {0.0, 1e-4}) {
                SCOPED_TRACE(testing::Message() << "seed " << seed << ", bin " << binSize << ", margin " << margin);
                const BinRegistry cpuBins = cpuSphereBins(s, grid, margin, dr.extra);
                for (const Spread& spread : SPREADS) {
                    const EmulatedDetection gpu =
                        emulateDetect(s, grid, margin, dr.rules.contactMask(), dr.extra, nullptr, nullptr, spread);
                    EXPECT_EQ(gpu.spheres.starts(grid.numBins()), cpuBins.start) << spread.binLanes << " lanes";
                    EXPECT_EQ(gpu.spheres.items, cpuBins.entries) << spread.binLanes << " lanes";
                }
                expectTheCpuDetectorsPairs(s, grid, margin, dr);
                cases++;
            }
        }
    }
    EXPECT_EQ(cases, 12);
}

// Detection in slabs of bin layers (kinematics/BinSlabs.h): each slab's spheres searched against
// that slab's bins only (its layers and a halo either side), twice (count, then fill), give the CPU
// detector's contact list pair for pair, in 2, 3 and as many slabs as layers (one layer each, where
// the halo is most of a slab), with meshes; in 3 or more slabs the largest slab's bins are fewer than
// the whole grid's.
TEST(CudaDetectionKernels, SlabsFindTheCpuDetectorsPairs) {
    const DetectionRules dr;
    int cases = 0;
    for (unsigned seed : {4u, 5u}) {
        SimState s = detectionState(sceneWithMeshes(seed, 1200), "CudaDetectionKernels");
        for (double binSize : {0.0032, 0.0045}) {
            const BinGrid grid = makeBinGrid(s, binSize);
            ASSERT_GE(grid.nz, 6);
            for (double margin : {0.0, 1e-4}) {
                SCOPED_TRACE(testing::Message() << "seed " << seed << ", bin " << binSize << ", margin " << margin);
                const float largest = *std::max_element(s.spheres.radius.begin(), s.spheres.radius.end());
                ASSERT_GT(centreReachFor(grid, margin, dr.extra, (double)largest), 0.0);  // by centres
                ContactDetector det;
                DetectedContacts cpu;
                double binning = 0.0, search = 0.0;
                det.detect(s, grid, margin, dr.rules.contactMask(), dr.extra, cpu, binning, search);
                const EmulatedDetection whole = emulateDetect(s, grid, margin, dr.rules.contactMask(), dr.extra);
                const size_t wholeWords = whole.spheres.start.size() + whole.spheres.items.size() +
                                          whole.triangles.start.size() + whole.triangles.items.size();
                for (int slabs : {2, 3, grid.nz}) {
                    SCOPED_TRACE(testing::Message() << slabs << " slabs of " << grid.nz << " layers");
                    const SlabDetection d =
                        emulateDetectInSlabs(s, grid, margin, dr.rules.contactMask(), dr.extra, slabs);
                    expectSameList(s, d.contacts, cpu, 20);
                    if (slabs >= 3) EXPECT_LT(d.largestBinWords, wholeWords);
                    cases++;
                }
            }
        }
    }
    EXPECT_EQ(cases, 24);
}

// Periodic axes (physics/Periodic.h): the kernels wrap bins around the periodic faces and compare
// geometries through their nearest images, spheres and the mesh floor that spans the whole period
// alike, pair for pair as the CPU's detector.
TEST(CudaDetectionKernels, MatchTheCpuDetectorWithPeriodicAxes) {
    const DetectionRules dr;
    int cases = 0;
    for (unsigned int axes : {3u, 7u}) {
        Scene scene = sceneWithMeshes(6, 1200);
        scene.periodicAxes = axes;
        SimState s = detectionState(scene, "CudaDetectionKernels");
        for (double binSize : {0.0015, 0.0037}) {
            SCOPED_TRACE(testing::Message() << "axes " << axes << ", bin " << binSize);
            expectTheCpuDetectorsPairs(s, makeBinGrid(s, binSize), 1e-4, dr);
            cases++;
        }
    }
    EXPECT_EQ(cases, 4);
}

// A sheared cell (Lees–Edwards, SetPeriodicShear): the image layers beyond the z faces are displaced
// along x by the offset; the kernels register and search them as the CPU's detector does, pair for
// pair, at offsets of a fraction of a bin, of several bins, and of nearly half the period.
TEST(CudaDetectionKernels, MatchTheCpuDetectorInAShearedCell) {
    const DetectionRules dr;
    int cases = 0;
    Scene scene = sceneWithMeshes(6, 1200);
    scene.periodicAxes = 7u;
    scene.sheared = true;
    scene.shearRate = 1.0;
    SimState s = detectionState(scene, "CudaDetectionKernels");
    ASSERT_EQ(s.frame.periodic.shear, 1u);
    for (double time : {0.0013, 0.37, -0.4999}) {
        s.frame.periodic.shearTime = time / s.frame.periodic.shearVelocity * s.frame.periodic.length.x;
        for (double binSize : {0.0015, 0.0037}) {
            SCOPED_TRACE(testing::Message() << "offset " << time << " Lx, bin " << binSize);
            expectTheCpuDetectorsPairs(s, makeBinGrid(s, binSize), 1e-4, dr);
            cases++;
        }
    }
    EXPECT_EQ(cases, 6);
}

// A ball among grains ten times smaller (a drop into a bed): its box spans some 1,700 bins of the
// grains' size, which one thread walked alone (DetectionLanes.h). Spread as the GPU spreads it here
// (16 threads an item in registration, the ball wide and searched by a warp), the kernels' list is
// still the CPU's, pair for pair, with the ball low in the scene's space-filling order (it reports
// over a hundred of its pairs itself) and high in it (the grains near it report most of them).
TEST(CudaDetectionKernels, MatchTheCpuDetectorWithABallAmongSmallGrains) {
    const DetectionRules dr;
    int cases = 0;
    for (float at : {-0.008f, 0.008f}) {
        Scene scene = randomScene(7, 1500);
        auto ballType = std::make_shared<DEMClumpTemplate>();
        ballType->mass = 1.f;
        ballType->MOI = make_float3(1.f);
        ballType->radii.push_back(0.009f);
        ballType->relPos.push_back(make_float3(0.f));
        ballType->materials.push_back(scene.materials.front());
        scene.batches.push_back(std::make_shared<DEMClumpBatch>(
            std::vector<std::shared_ptr<DEMClumpTemplate>>{ballType}, std::vector<float3>{make_float3(at, at, at)}));
        SimState s = detectionState(scene, "CudaDetectionKernels");
        const bodyID_t ballId =
            (bodyID_t)(std::find(s.spheres.radius.begin(), s.spheres.radius.end(), 0.009f) - s.spheres.radius.begin());
        ASSERT_LT((size_t)ballId, s.spheres.size());
        const double margin = 1e-4;
        const BinGrid grid = makeBinGrid(s, 0.0011);
        const double reach = 0.009 + margin + 2e-4;  // the largest extra margin is family 1's
        ASSERT_GT(cuda::maxBinRows(grid, reach), 256u);
        Spread spread;
        spread.binLanes = cuda::binningLanes((unsigned int)s.spheres.size(), false, grid, reach);
        EXPECT_EQ(spread.binLanes, cuda::MAX_BINNING_LANES);
        spread.wideRadius = cuda::wideSphereRadius(grid);
        spread.searchLanes = cuda::searchLanes((unsigned int)s.spheres.size(), false, grid, 0.0003 + margin);
        EXPECT_GT(spread.searchLanes, 1u);
        EXPECT_EQ(std::count_if(s.spheres.radius.begin(), s.spheres.radius.end(),
                                [&](float r) { return r >= spread.wideRadius; }),
                  1);
        ContactDetector det;
        DetectedContacts cpu;
        double binning = 0.0, search = 0.0;
        det.detect(s, grid, margin, dr.rules.contactMask(), dr.extra, cpu, binning, search);
        size_t ballAsA = 0, ballAsB = 0;
        for (size_t k = 0; k < cpu.size(); k++) {
            ballAsA += cpu.geomA[k] == ballId;
            ballAsB += cpu.geomB[k] == ballId;
        }
        SCOPED_TRACE(testing::Message() << "ball at " << at << ", id " << ballId << " of " << s.spheres.size()
                                        << ", its pairs as A " << ballAsA << ", as B " << ballAsB);
        EXPECT_GT(ballAsA + ballAsB, 200u);
        if (at < 0.f)
            EXPECT_GT(ballAsA, 100u);  // the ball's lanes fill and rank a long list
        else
            EXPECT_GT(ballAsB, 4 * ballAsA);  // the grains find the ball
        const EmulatedDetection gpu =
            emulateDetect(s, grid, margin, dr.rules.contactMask(), dr.extra, nullptr, nullptr, spread);
        EXPECT_EQ(gpu.contacts.geomA, cpu.geomA);
        EXPECT_EQ(gpu.contacts.geomB, cpu.geomB);
        cases++;
    }
    EXPECT_EQ(cases, 2);
}

// Threads an item in registration: one per row of bins of the largest box, up to 16, below 2^18
// searched spheres; one above, and with the active box's dormant registry. Threads a sphere in the
// search: the same from the smallest box. Wide spheres from twice the smallest bin edge. Spheres
// binned by their centres from 2^18 searched spheres. The diagnostic switches' numbers where they
// are set, and an error naming the variable for anything else.
TEST(CudaDetectionKernels, SpreadFollowsTheLargestBoxAndTheSceneSize) {
    BinGrid g{make_double3(0, 0, 0), 1.0, make_double3(1, 1, 1), 100, 100, 100, 0u};
    ScopedEnvironmentVariable unsetLanes("DEME_CUDA_BINNING_LANES", "");
    ScopedEnvironmentVariable unsetWide("DEME_CUDA_WIDE_SPHERES", "");
    ScopedEnvironmentVariable unsetSearch("DEME_CUDA_SEARCH_LANES", "");
    ScopedEnvironmentVariable unsetCentre("DEME_CUDA_CENTRE_BINNING", "");
    EXPECT_FALSE(cuda::centreBinning(cuda::DETECTION_LANES_BELOW - 1));
    EXPECT_TRUE(cuda::centreBinning(cuda::DETECTION_LANES_BELOW));
    EXPECT_EQ(cuda::maxBinRows(g, 0.4), 4u);   // a box 0.8 wide spans at most 2 bins an axis
    EXPECT_EQ(cuda::maxBinRows(g, 1.0), 16u);  // 2.0 wide: at most 4
    EXPECT_EQ(cuda::binningLanes(1000, false, g, 0.4), 4u);
    EXPECT_EQ(cuda::binningLanes(1000, false, g, 1.0), 16u);
    EXPECT_EQ(cuda::binningLanes(1000, false, g, 5.0), 16u);
    EXPECT_EQ(cuda::binningLanes(cuda::DETECTION_LANES_BELOW - 1, false, g, 5.0), 16u);
    EXPECT_EQ(cuda::binningLanes(cuda::DETECTION_LANES_BELOW, false, g, 5.0), 1u);
    EXPECT_EQ(cuda::binningLanes(1000, true, g, 5.0), 1u);
    EXPECT_EQ(cuda::searchLanes(1000, false, g, 0.4), 4u);
    EXPECT_EQ(cuda::searchLanes(1000, false, g, 5.0), 16u);
    EXPECT_EQ(cuda::searchLanes(cuda::DETECTION_LANES_BELOW, false, g, 0.4), 1u);
    EXPECT_EQ(cuda::searchLanes(1000, true, g, 0.4), 1u);
    EXPECT_EQ(cuda::wideSphereRadius(g), 2.f);
    g.edge.y = 0.75;
    EXPECT_EQ(cuda::wideSphereRadius(g), 1.5f);
    {
        ScopedEnvironmentVariable lanes("DEME_CUDA_BINNING_LANES", "32");
        ScopedEnvironmentVariable wide("DEME_CUDA_WIDE_SPHERES", "0");
        ScopedEnvironmentVariable search("DEME_CUDA_SEARCH_LANES", "5");
        ScopedEnvironmentVariable centre("DEME_CUDA_CENTRE_BINNING", "1");
        EXPECT_TRUE(cuda::centreBinning(1000));
        EXPECT_EQ(cuda::searchLanes(1u << 20, false, g, 0.4), 5u);
        EXPECT_EQ(cuda::searchLanes(1000, true, g, 0.4), 1u);
        EXPECT_EQ(cuda::binningLanes(1u << 20, false, g, 0.4), 32u);
        EXPECT_EQ(cuda::binningLanes(1000, true, g, 0.4), 1u);
        EXPECT_EQ(cuda::wideSphereRadius(g), std::numeric_limits<float>::infinity());
    }
    auto expectError = [](const char* name, const char* bad, auto call) {
        ScopedEnvironmentVariable v(name, bad);
        try {
            call();
            ADD_FAILURE() << "no error for " << name << "=" << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(std::string(name) + " is '" + bad + "'"), std::string::npos)
                << e.what();
        }
    };
    for (const char* bad : {"0", "65", "4x", "-1"})
        expectError("DEME_CUDA_BINNING_LANES", bad, [&] { cuda::binningLanes(1000, false, g, 1.0); });
    for (const char* bad : {"0", "65", "x"})
        expectError("DEME_CUDA_SEARCH_LANES", bad, [&] { cuda::searchLanes(1000, false, g, 1.0); });
    for (const char* bad : {"2", "yes", "-0"})
        expectError("DEME_CUDA_WIDE_SPHERES", bad, [&] { cuda::wideSphereRadius(g); });
    {
        ScopedEnvironmentVariable never("DEME_CUDA_CENTRE_BINNING", "0");
        EXPECT_FALSE(cuda::centreBinning(1u << 20));
    }
    for (const char* bad : {"2", "on"})
        expectError("DEME_CUDA_CENTRE_BINNING", bad, [&] { cuda::centreBinning(1000); });
}

// The active box: with a dormant family (fixed, no contacts among fixed families) the kernels build
// the dormant registry (moving spheres listed, dormant ones by centre bin) and search the moving
// spheres only, as DeviceDormantRegistry and CudaKinematics::detect run them. The registry and the
// contact list must be the CPU's cached detector's (backend/cpu/DormantCache.h, itself checked
// against brute force by ActiveBoxDetection.DormantCacheFindsExactlyTheFullSearchsPairs), pair for
// pair and in order, for three margins, after a family change, with a still mesh floor, and with a
// wall that moves (both fall back to the full search).
TEST(CudaDetectionKernels, DormantRegistryMatchesTheCpuCachedDetectorExactly) {
    FamilyRules rules;
    rules.motion(2).fixed = true;   // family 2 is dormant: fixed, ...
    rules.setContact(2, 2, false);  // ... no contacts among its grains
    float extra[NUM_FAMILIES] = {};
    extra[1] = 2e-4f;
    extra[2] = 1e-4f;  // dormant grains reach further: the search box grows by it
    uint8_t dormant[NUM_FAMILIES], prescribed[NUM_FAMILIES];
    rules.dormantFamilies(dormant);
    rules.prescribedFamilies(prescribed);
    ASSERT_EQ(dormant[2], 1);
    int cases = 0;
    for (unsigned seed : {1u, 2u}) {
        SimState s = detectionState(randomSceneOnMeshFloor(seed, 1200), "CudaDetectionKernels");
        ASSERT_GT(s.triangles.size(), 200u);
        const BinGrid grid = makeBinGrid(s, 0.0015);
        ContactDetector det;
        det.setFamilies(dormant, prescribed, s);
        auto compare = [&](double margin, bool expectRegistry) {
            SCOPED_TRACE(testing::Message() << "seed " << seed << ", margin " << margin);
            std::vector<uint8_t> movable(s.owners.size(), 0);
            for (size_t k = 0; k < s.analytical.size(); k++)
                movable[s.analytical.owner[k]] = ownerCanMove(s, prescribed, s.analytical.owner[k]);
            for (size_t k = 0; k < s.triangles.size(); k++)
                movable[s.triangles.owner[k]] = ownerCanMove(s, prescribed, s.triangles.owner[k]);
            const EmulatedDetection gpu =
                emulateDetect(s, grid, margin, rules.contactMask(), extra, dormant, movable.data());
            DetectedContacts cpu;
            double binning = 0.0, search = 0.0;
            det.detect(s, grid, margin, rules.contactMask(), extra, cpu, binning, search);
            EXPECT_EQ(gpu.usedRegistry, expectRegistry);
            if (expectRegistry) {
                const DormantCache& c = det.dormantCache();
                EXPECT_EQ(gpu.registry.moving, c.moving());
                const DormantBinsView cv = c.view();
                const size_t numBins = grid.numBins();
                EXPECT_EQ(gpu.registry.start, std::vector<unsigned int>(cv.start, cv.start + numBins + 1));
                EXPECT_EQ(gpu.registry.sortedItems, std::vector<unsigned int>(cv.items, cv.items + cv.start[numBins]));
                EXPECT_EQ(gpu.registry.maxReach, cv.maxReach);
                EXPECT_LT(c.moving().size(), s.spheres.size());
                EXPECT_GT(c.moving().size(), 0u);
            }
            expectSameList(s, gpu.contacts, cpu, 5);
            cases++;
        };
        for (double margin : {0.0, 1e-4, 3e-4}) compare(margin, true);
        // A grain wakes up, another falls dormant.
        ASSERT_TRUE(wakeOneAndFreezeOne(s, 2, 0));
        compare(2e-4, true);
        // A wall that moves and reaches dormant grains: the full search.
        s.owners.vel[s.analytical.owner[0]] = make_float3(0, 0, 0.1f);
        det.setFamilies(dormant, prescribed, s);
        compare(1e-4, false);
    }
    EXPECT_EQ(cases, 10);
}

// The case the counting sort's shifted starts exist for: items in a thin slab of a tall grid, so that
// long runs of bins below and above hold nothing. Every bin's start must still be the first entry at
// or after it, the last one the number of entries, and each bin's items in increasing order.
TEST(CudaDetectionKernels, BinStartsOfAMostlyEmptyGrid) {
    const BinGrid g{make_double3(0, 0, 0), 1.0, make_double3(1, 1, 1), 4, 4, 50, 0u};
    const size_t numBins = 4 * 4 * 50;
    // Three boxes at z in [20, 22): items 0 and 1 share bins. As bin ranges, and as the boxes
    // (triangles' boxes here, read from DetectionArgs) that cover them.
    std::vector<int> lo = {0, 0, 20, 1, 1, 20, 3, 3, 21}, hi = {1, 1, 21, 2, 2, 21, 3, 3, 21};
    std::vector<double3> boxLo(3), boxHi(3);
    for (unsigned int i = 0; i < 3; i++) {
        boxLo[i] = make_double3(lo[3 * i] + 0.25, lo[3 * i + 1] + 0.25, lo[3 * i + 2] + 0.25);
        boxHi[i] = make_double3(hi[3 * i] + 0.75, hi[3 * i + 1] + 0.75, hi[3 * i + 2] + 0.75);
    }
    DetectionArgs args{};
    args.grid = g;
    args.triLo = boxLo.data();
    args.triHi = boxHi.data();
    const StateView none{};
    std::vector<std::pair<unsigned int, unsigned int>> entries;  // (bin, item), from the boxes by hand
    for (unsigned int i = 0; i < 3; i++)
        for (int z = lo[3 * i + 2]; z <= hi[3 * i + 2]; z++)
            for (int y = lo[3 * i + 1]; y <= hi[3 * i + 1]; y++)
                for (int x = lo[3 * i]; x <= hi[3 * i]; x++) entries.push_back({(unsigned int)binIndex(g, x, y, z), i});
    std::sort(entries.begin(), entries.end());
    std::vector<unsigned int> start(numBins + 2, 0);
    const LayerRange whole = wholeGridSlab(g).binned;
    runThreads(3, [&] { deme_bin_count(none, args, BINNED_TRIANGLES, nullptr, 3, 1u, whole, start.data()); });
    exclusiveSum(start);
    ASSERT_EQ(start[numBins + 1], 17u);
    std::vector<unsigned int> items(17, 99);
    runThreadsReversed(
        3, [&] { deme_bin_scatter(none, args, BINNED_TRIANGLES, nullptr, 3, 1u, whole, start.data(), items.data()); });
    runThreads(numBins, [&] { deme_bin_sort(start.data(), numBins, items.data()); });
    for (size_t b = 0; b <= numBins; b++) {
        const auto first = std::lower_bound(entries.begin(), entries.end(), std::make_pair((unsigned int)b, 0u));
        ASSERT_EQ(start[b], (unsigned int)(first - entries.begin())) << "bin " << b;
    }
    for (size_t k = 0; k < entries.size(); k++) EXPECT_EQ(items[k], entries[k].second) << "entry " << k;
    EXPECT_EQ(start[numBins], 17u);
    EXPECT_EQ(start[0], 0u);
    // Bin (1, 1, 20) holds items 0 and 1, in that order.
    const size_t shared = 1 + 4 * (1 + 4 * 20);
    ASSERT_EQ(start[shared + 1] - start[shared], 2u);
    EXPECT_EQ(items[start[shared]], 0u);
    EXPECT_EQ(items[start[shared] + 1], 1u);

    // A slab of layers [21, 30) (kinematics/BinSlabs.h): the boxes cut to it, its bins' starts from
    // layer 21's first bin on: the entries of z = 21 only, as above.
    const LayerRange slab{21, 30};
    const size_t slabBins = 4 * 4 * 9, first = firstBinOfLayer(g, 21);
    EXPECT_EQ(first, (size_t)binIndex(g, 0, 0, 21));
    std::vector<unsigned int> slabStart(slabBins + 2, 0);
    runThreads(3, [&] { deme_bin_count(none, args, BINNED_TRIANGLES, nullptr, 3, 1u, slab, slabStart.data()); });
    exclusiveSum(slabStart);
    std::vector<unsigned int> slabItems(slabStart[slabBins + 1], 99);
    runThreadsReversed(3, [&] {
        deme_bin_scatter(none, args, BINNED_TRIANGLES, nullptr, 3, 1u, slab, slabStart.data(), slabItems.data());
    });
    runThreads(slabBins, [&] { deme_bin_sort(slabStart.data(), slabBins, slabItems.data()); });
    std::vector<std::pair<unsigned int, unsigned int>> inSlab;
    for (const auto& e : entries)
        if (e.first >= first) inSlab.push_back({e.first - (unsigned int)first, e.second});
    ASSERT_EQ(inSlab.size(), 9u);  // items 0 and 1: 4 bins each at z = 21; item 2: 1
    ASSERT_EQ(slabItems.size(), inSlab.size());
    for (size_t b = 0; b <= slabBins; b++) {
        const auto at = std::lower_bound(inSlab.begin(), inSlab.end(), std::make_pair((unsigned int)b, 0u));
        ASSERT_EQ(slabStart[b], (unsigned int)(at - inSlab.begin())) << "slab bin " << b;
    }
    for (size_t k = 0; k < inSlab.size(); k++) EXPECT_EQ(slabItems[k], inSlab[k].second) << "slab entry " << k;
    // A view of the slab reads bin (1, 1, 21)'s two items by its index in the whole grid.
    const BinsView view{slabStart.data(), slabItems.data(), first};
    const uint64_t bin = binIndex(g, 1, 1, 21);
    ASSERT_EQ(view.end(bin) - view.first(bin), 2u);
    EXPECT_EQ(slabItems[view.first(bin)], 0u);
    EXPECT_EQ(slabItems[view.first(bin) + 1], 1u);
}
