#include "backend/cuda/CudaKinematics.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include <deme/Error.h>

#include <cuda_runtime_api.h>

#include "backend/cuda/CudaCheck.h"
#include "backend/cuda/CudaModule.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/DetectionLanes.h"
#include "backend/cuda/DevicePrimitives.h"
#include "backend/cuda/EmbeddedKernel.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "kinematics/DetectionRules.h"
#include "runtime/DetectionSlabs.h"
#include "runtime/IndexLimits.h"
#include "runtime/MemoryEstimate.h"
#include "runtime/RebuiltArrays.h"
#include "state/StateView.h"

namespace deme::cuda {

namespace {

constexpr unsigned int THREADS = 256;
constexpr const char* CALL = "DoDynamics";

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

cudaStream_t toCuda(Stream s) { return static_cast<cudaStream_t>(s); }

// Runs f with GPU `device` current for this thread, then makes `back` current again: kT sizes the
// outbox, which lives on dT's GPU, from its own thread.
template <class F>
void onDevice(int device, int back, F&& f) {
    if (device == back) {
        f();
        return;
    }
    DEME_CUDA_CHECK(CALL, cudaSetDevice(device));
    try {
        f();
    } catch (...) {
        cudaSetDevice(back);
        throw;
    }
    DEME_CUDA_CHECK(CALL, cudaSetDevice(back));
}

// Items registered in bins (spheres or triangles).
// A kind of items' bins (deme_bin_count and what follows it in kernels/Detection.cu): per bin its
// first entry (numBins + 2, the last the entries' count); the entries. (Which bins an item covers
// is computed from its box where needed, not stored.)
struct DeviceBins {
    DeviceBuffer<unsigned int> start, items;
};

}  // namespace

// kT's side: everything here is on kT's GPU and used only by kT's thread.
struct CudaKinematics::Work {
    int device = 0, dTDevice = 0;
    bool staged = false;  // kT on another GPU than dT: copy the snapshot in and the contact list out
    // Not staged: the spheres' owners and radii are read from dT's own state (INPUT fields, which
    // change only while kT is idle); staged, from the copies below.
    const DeviceState* shared = nullptr;
    Stream stream = nullptr;
    CudaModule module;
    CudaKernel kTriBoxes, kBinCount, kBinScatter, kBinSort, kPairSearch, kPairSearchLanes, kPairOrder, kPairSearchWide,
        kPairRankWide, kPairFinishWide;
    PairAKernels pairAKernels;  // the outbox's As made compact (backend/cuda/DevicePairA.h)
    DevicePrimitives prim;
    DeviceDormantRegistry dormant;  // the active box: dormant spheres registered once
    // Static geometry (a copy of Geometry).
    DeviceBuffer<bodyID_t> sphereOwner, anaOwner, triOwner;
    DeviceBuffer<float> radius, anaRadius, familyExtraMargin;
    double sharedExtraMargin = -1.0;  // DetectionArgs::sharedExtraMargin of familyExtraMargin
    // The smallest and largest sphere, the largest family extra margin (DetectionLanes.h).
    double minRadius = 0.0, maxRadius = 0.0, maxExtraMargin = 0.0;
    DeviceBuffer<bodyID_t> wideSpheres;              // searched by several threads each (DetectionLanes.h)
    float wideRadius = 0.f;
    DeviceBuffer<uint8_t> anaType, anaInside, familyMask;
    BinGrid grid{};
    DomainFrame frame{};
    uint32_t numOwners = 0, numSpheres = 0, numAnalytical = 0, numTriangles = 0;
    bool spheresAreOwners = false;  // (Geometry's)
    // The snapshot and the contact list on this GPU, when staged.
    KinematicsInbox localIn;
    KinematicsOutbox localOut;
    // Scratch.
    DeviceBins sphereBins, triBins;
    DeviceBuffer<double3> triLo, triHi;
    DeviceBuffer<PairOffset> pairOffset;    // each searched sphere's pair count, then (in place) offset
    DeviceBuffer<unsigned int> wideCursor;  // each wide sphere's partners written so far
    DeviceBuffer<unsigned int> laneCursor;  // each sphere's, where several threads search it
    DeviceBuffer<uint64_t> countSum;        // scanCounts's total in 64 bits
    // The pairs' As whole, where the search does not leave them implied by the offsets (several
    // threads a sphere, wide spheres, the dormant registry), and the compact form's rows.
    DeviceBuffer<bodyID_t> wholeA;
    DeviceBuffer<uint32_t> pairARows;
    size_t lastPairs = 0;                   // the last detection's pairs (plans the next one's slabs)

    ~Work() {
        if (stream && cudaStreamDestroy(toCuda(stream)) != cudaSuccess) cudaGetLastError();
    }
    void upload(const Geometry& g);
    // Counts [0, entries) (the last one zero) into their exclusive sum in place; returns the total
    // (the last entry's offset). A total past 2^32 - 1, which the 32-bit sum would wrap, is a
    // deme::Error naming `what` (runtime/IndexLimits.h).
    unsigned int scanCounts(DeviceBuffer<unsigned int>& counts, size_t entries, const char* what, const char* remedy);
    // The same of the pair counts (pairOffset's first `entries`), in 64 bits: a GPU set may pass 2^32
    // pairs; one past MAX_GPU_CONTACT_PAIRS is a deme::Error (runtime/IndexLimits.h).
    size_t scanPairCounts(size_t entries);
    // inPlace: reads dT's state (shared), not the inbox, and lets go of the scratch at the end
    // where it holds more than keepScratchUpTo bytes.
    void detect(const DetectionOrder& o, bool inPlace, size_t keepScratchUpTo, void* submitted, KinematicsInbox& in,
                KinematicsOutbox& out, DetectionReport& r);
    size_t scratchBytes() const;
    // The spheres' and triangles' bins (the first of the scratch to go, before the As are made
    // compact), and all of it.
    void releaseBins();
    void releaseScratch();
};

void KinematicsInbox::setGroup(MemoryGroup g) {
    forEachBuffer([g](auto& b) { b.setGroup(g); });
}

size_t KinematicsInbox::bytes() const {
    size_t n = 0;
    const_cast<KinematicsInbox*>(this)->forEachBuffer([&n](const auto& b) { n += b.capacityBytes(); });
    return n;
}

void KinematicsInbox::release() {
    forEachBuffer([](auto& b) { b.release(); });
}

void KinematicsInbox::resize(bool spheresAreOwners, size_t numOwners, size_t numSpheres, size_t numAnalytical,
                             size_t numTriangles) {
    // The form the layout does not read goes (after a layout switch it holds memory).
    if (spheresAreOwners) {
        spherePos.release();
        voxel.resizeDiscarding(numSpheres);
        subX.resizeDiscarding(numSpheres);
        subY.resizeDiscarding(numSpheres);
        subZ.resizeDiscarding(numSpheres);
    } else {
        voxel.release();
        subX.release();
        subY.release();
        subZ.release();
        spherePos.resizeDiscarding(numSpheres);
    }
    triVert.resizeDiscarding(3 * numTriangles);
    analPos.resizeDiscarding(numAnalytical);
    analDir.resizeDiscarding(numAnalytical);
    ownerFamily.resizeDiscarding(numOwners);
}

void KinematicsInbox::copyFrom(const KinematicsInbox& src, Stream stream) {
    forEachBuffer([stream](auto& to, const auto& from) { to.copyFromAsync(from, to.size(), stream); },
                  const_cast<KinematicsInbox&>(src));
}

void CudaKinematics::Work::upload(const Geometry& g) {
    uploadResized(sphereOwner, g.sphereOwner, stream);  // empty where not staged
    uploadResized(radius, g.radius, stream);
    uploadResized(anaOwner, g.anaOwner, stream);
    uploadResized(anaType, g.anaType, stream);
    uploadResized(anaRadius, g.anaRadius, stream);
    uploadResized(anaInside, g.anaInside, stream);
    uploadResized(triOwner, g.triOwner, stream);
    uploadResized(familyMask, g.familyMask, stream);
    uploadResized(familyExtraMargin, g.familyExtraMargin, stream);
    sharedExtraMargin = sharedExtraMarginOf(g.familyExtraMargin.data());
    minRadius = g.minRadius;
    maxRadius = g.maxRadius;
    uploadResized(wideSpheres, g.wideSpheres, stream);
    wideRadius = g.wideRadius;
    maxExtraMargin = 0.0;
    for (float e : g.familyExtraMargin) maxExtraMargin = std::max(maxExtraMargin, (double)e);
    dormant.upload(g.dormant, stream);  // built afresh at the next detection
    grid = g.grid;
    frame = g.frame;
    numOwners = g.numOwners;
    numSpheres = g.numSpheres;
    numAnalytical = g.numAnalytical;
    numTriangles = g.numTriangles;
    spheresAreOwners = g.spheresAreOwners;
    if (staged) localIn.resize(spheresAreOwners, numOwners, numSpheres, numAnalytical, numTriangles);
    // The host vectors stay dT's: wait until the copies have read them.
    synchronize(stream);
}

unsigned int CudaKinematics::Work::scanCounts(DeviceBuffer<unsigned int>& counts, size_t entries, const char* what,
                                              const char* remedy) {
    countSum.resizeDiscarding(1);
    prim.sum(counts.data(), countSum.data(), entries, stream);
    prim.exclusiveSum(counts.data(), counts.data(), entries, stream);
    uint64_t wide = 0;
    unsigned int total = 0;
    countSum.downloadAsync(&wide, 1, stream);
    counts.downloadAsync(&total, 1, stream, entries - 1);
    synchronize(stream);
    requireIndexable(wide, what, remedy, CALL);
    return total;
}

size_t CudaKinematics::Work::scanPairCounts(size_t entries) {
    prim.exclusiveSum((const uint64_t*)pairOffset.data(), (uint64_t*)pairOffset.data(), entries, stream);
    PairOffset total = 0;
    pairOffset.downloadAsync(&total, 1, stream, entries - 1);
    synchronize(stream);
    requireGpuPairCount(total, CALL);
    return total;
}

// What a detection keeps from one to the next that the next rebuilds anyway.
size_t CudaKinematics::Work::scratchBytes() const {
    return sphereBins.start.capacityBytes() + sphereBins.items.capacityBytes() + triBins.start.capacityBytes() +
           triBins.items.capacityBytes() + triLo.capacityBytes() + triHi.capacityBytes() + pairOffset.capacityBytes() +
           wideCursor.capacityBytes() + laneCursor.capacityBytes() + countSum.capacityBytes() + wholeA.capacityBytes() +
           pairARows.capacityBytes() + prim.scratchBytes();
}

void CudaKinematics::Work::releaseBins() {
    sphereBins.start.release();
    sphereBins.items.release();
    triBins.start.release();
    triBins.items.release();
}

void CudaKinematics::Work::releaseScratch() {
    releaseBins();
    triLo.release();
    triHi.release();
    pairOffset.release();
    wideCursor.release();
    laneCursor.release();
    countSum.release();
    wholeA.release();
    pairARows.release();
    prim.releaseScratch();
}

// The rules of kinematics/DetectionRules.h in kernels (kernels/Detection.cu), bins sorted with CUB.
void CudaKinematics::Work::detect(const DetectionOrder& o, bool inPlace, size_t keepScratchUpTo, void* submitted,
                                  KinematicsInbox& in, KinematicsOutbox& out, DetectionReport& r) {
    const double t0 = now();
    // The snapshot is complete (in place: dT's steps have finished) once dT's stream has passed the
    // event (an event of another GPU is fine for cudaStreamWaitEvent).
    DEME_CUDA_CHECK(CALL, cudaStreamWaitEvent(toCuda(stream), static_cast<cudaEvent_t>(submitted), 0));
    KinematicsInbox& src = staged ? localIn : in;
    // What moves, from the snapshot or (in place) from dT's state: the spheres' centres are their
    // owners', decoded from their compact positions, where spheres are owners (state/SphereLayout.h).
    const DeviceBuffer<double3>& centres = inPlace ? shared->cache.spherePos : src.spherePos;
    const DeviceBuffer<voxelID_t>& voxel = inPlace ? shared->owners.voxel : src.voxel;
    const DeviceBuffer<subVoxelPos_t>& subX = inPlace ? shared->owners.subX : src.subX;
    const DeviceBuffer<subVoxelPos_t>& subY = inPlace ? shared->owners.subY : src.subY;
    const DeviceBuffer<subVoxelPos_t>& subZ = inPlace ? shared->owners.subZ : src.subZ;
    const DeviceBuffer<double3>& triVert = inPlace ? shared->cache.triVert : src.triVert;
    const DeviceBuffer<double3>& analPos = inPlace ? shared->cache.analPos : src.analPos;
    const DeviceBuffer<double3>& analDir = inPlace ? shared->cache.analDir : src.analDir;
    const DeviceBuffer<family_t>& ownerFamily = inPlace ? shared->owners.family : src.ownerFamily;
    if (staged) localIn.copyFrom(in, stream);
    // The state as the detection kernels read it: static geometry here, positions from the snapshot.
    StateView v{};
    v.frame = frame;
    v.frame.periodic.shearTime = o.shearTime;  // a sheared cell's image offset: the snapshot's
    v.frame.periodic.shearClock = nullptr;
    v.owners.family = const_cast<family_t*>(ownerFamily.data());
    // (The view's pointers are writable; detection only reads them.)
    v.spheres.owner = staged ? sphereOwner.data() : const_cast<bodyID_t*>(shared->spheres.owner.data());
    v.spheres.radius = staged ? radius.data() : const_cast<float*>(shared->spheres.radius.data());
    v.analytical.owner = anaOwner.data();
    v.analytical.type = anaType.data();
    v.analytical.radius = anaRadius.data();
    v.analytical.inside = anaInside.data();
    v.triangles.owner = triOwner.data();
    v.cache.spherePos = const_cast<double3*>(centres.data());
    // Where spheres are their owners sphere i's centre is owner i's, decoded from its compact
    // position in the frame (a parked clump's on the frame's parking line), and its owner is i: the
    // state keeps no sphere owners to read (state/SphereLayout.h).
    v.spheresAreOwners = spheresAreOwners;
    v.owners.voxel = const_cast<voxelID_t*>(voxel.data());
    v.owners.subX = const_cast<subVoxelPos_t*>(subX.data());
    v.owners.subY = const_cast<subVoxelPos_t*>(subY.data());
    v.owners.subZ = const_cast<subVoxelPos_t*>(subZ.data());
    v.cache.analPos = const_cast<double3*>(analPos.data());
    v.cache.analDir = const_cast<double3*>(analDir.data());
    v.cache.triVert = const_cast<double3*>(triVert.data());
    v.numOwners = numOwners;
    v.numSpheres = numSpheres;
    v.numAnalytical = numAnalytical;
    v.numTriangles = numTriangles;
    const unsigned int nS = numSpheres, nT = numTriangles;
    DetectionArgs args{withShearOffset(grid, v.frame.periodic),
                       o.detectionMargin(),
                       familyExtraMargin.data(),
                       familyMask.data(),
                       {},
                       {},
                       nullptr,
                       nullptr,
                       sharedExtraMargin};
    // The active box: with dormant spheres registered, only the moving ones (`ids`) are binned and
    // searched, and find their dormant partners in the registry.
    const bool useDormant =
        dormant.prepare(v, grid, ownerFamily, numOwners, familyMask.data(), familyExtraMargin.data(), prim, stream);
    const bodyID_t* ids = useDormant ? dormant.moving() : nullptr;  // null: every sphere
    const unsigned int nSearched = useDormant ? dormant.numMoving() : nS;
    const DormantBinsView dormantBins = useDormant ? dormant.view() : DormantBinsView{nullptr, nullptr, 0.0};
    // Spheres by centre where none reaches far beyond a bin (kinematics/DetectionRules.h): then a
    // sphere is one bin entry, registered by one thread. At lab scale (DetectionLanes.h) by their
    // boxes still: there a detection is latency bound and its bytes do not matter, and a grain's
    // search box grown by the largest reach holds more rows than the lanes split (centreBinning).
    args.centreReach =
        centreBinning(nSearched) ? centreReachFor(args.grid, maxRadius + o.detectionMargin() + maxExtraMargin) : 0.0;
    // Threads an item in registration and a sphere in the pair search (DetectionLanes.h); triangles
    // keep one each.
    const unsigned int lanes = args.centreReach > 0.0 ? 1u
                                                      : binningLanes(nSearched, useDormant, grid,
                                                                     maxRadius + o.detectionMargin() + maxExtraMargin);
    const unsigned int sLanes = searchLanes(nSearched, useDormant, grid, minRadius + o.detectionMargin());
    const unsigned long long laneThreads = (unsigned long long)nSearched * sLanes;
    // Wide spheres, searched by several threads each (none with the dormant registry, whose searches
    // take one thread a sphere).
    const unsigned int nWide = useDormant ? 0u : (unsigned int)wideSpheres.size();
    const float searchWideFrom = nWide ? wideRadius : std::numeric_limits<float>::infinity();
    const unsigned long long wideThreads = (unsigned long long)nWide * WIDE_SPHERE_LANES;

    // Bins in slabs of layers where a scene's whole grid of them would not fit in the device's free
    // memory beside the offsets and the outbox's pairs (as many as the last detection found, and a
    // quarter more; the estimate's six a sphere at the first) (runtime/DetectionSlabs.h; a sphere by
    // its centre, one thread each, no registry, no wide sphere): the bins of each slab but the last
    // are made twice, once to count its spheres' partners and once, after the outbox is sized, to
    // fill them. Otherwise one slab, the whole grid, as before.
    const int kinds = nT ? 2 : 1;
    const bool slabbable = args.centreReach > 0.0 && !useDormant && lanes == 1 && sLanes == 1 && nWide == 0;
    int slabs = 1;
    if (slabbable) {
        size_t freeBytes = 0, totalBytes = 0;
        DEME_CUDA_CHECK(CALL, cudaMemGetInfo(&freeBytes, &totalBytes));
        // Within DEME_MEMORY_LIMIT where set: what the run may still take.
        if (const size_t limit = memoryLimit(0, CALL)) {
            const size_t held = deviceBytesAllocated();
            freeBytes = std::min(freeBytes, limit > held ? limit - held : (size_t)0);
        }
        const double pairs = lastPairs ? 1.25 * (double)lastPairs : ESTIMATED_PAIRS_PER_SPHERE * (double)nSearched;
        // (The outbox's pairs: B, and A compact with its rows, 5.25 B a pair: state/CompactPairA.h.)
        const double besides =
            (double)sizeof(PairOffset) * ((double)nSearched + 1.0) + (sizeof(bodyID_t) + 1.25) * pairs;
        slabs = detectionSlabCount(grid, args.centreReach, kinds, (double)nSearched, (double)nSearched, besides,
                                   (double)freeBytes);
    }
    const int halo = slabs > 1 ? slabHalo(grid, args.centreReach) : 0;
    auto slabAt = [&](int k) { return slabs > 1 ? binSlab(grid, halo, slabs, k) : wholeGridSlab(grid); };
    if (slabs > 1) {
        // Room for the thickest slab's starts at once: grown slab by slab (by half again each time)
        // they would hold more than any slab needs.
        uint64_t thickest = 0;
        for (int k = 0; k < slabs; k++) thickest = std::max(thickest, slabAt(k).numBins(grid));
        sphereBins.start.reserve(thickest + 2);
        if (nT) triBins.start.reserve(thickest + 2);
    }

    // 1. Bins of every geometry enlarged by its margin, in the layers of `slab`: of items ids[0, n)
    // (all `items` if null), by a counting sort (kernels/Detection.cu, deme_bin_count): 4 bytes per
    // entry and per bin.
    auto binItems = [&](DeviceBins& b, BinnedKind kind, const bodyID_t* ids, unsigned int n, unsigned int itemLanes,
                        const BinSlab& slab) {
        const uint64_t slabBins = slab.numBins(grid);
        b.start.resizeDiscarding(slabBins + 2);
        b.start.zeroAsync(stream);
        const unsigned long long threads = (unsigned long long)n * itemLanes;
        if (n)
            launch(kBinCount, blocksFor(threads, THREADS), THREADS, 0, stream, v, args, (unsigned int)kind, ids, n,
                   itemLanes, slab.binned, b.start.data());
        const unsigned int entries = scanCounts(b.start, slabBins + 2, "bin entries", FEWER_BIN_ENTRIES_REMEDY);
        b.items.resizeDiscarding(entries);
        if (entries) {
            launch(kBinScatter, blocksFor(threads, THREADS), THREADS, 0, stream, v, args, (unsigned int)kind, ids, n,
                   itemLanes, slab.binned, b.start.data(), b.items.data());
            launch(kBinSort, blocksFor(slabBins, THREADS), THREADS, 0, stream, (const unsigned int*)b.start.data(),
                   (unsigned long long)slabBins, b.items.data());
        }
    };
    triLo.resizeDiscarding(nT);
    triHi.resizeDiscarding(nT);
    args.triLo = triLo.data();
    args.triHi = triHi.data();
    if (nT) launch(kTriBoxes, blocksFor(nT, THREADS), THREADS, 0, stream, v, args, triLo.data(), triHi.data());
    // A slab's bins, spheres' and triangles' (no triangles, no bins for them, and no host round trip
    // to size them), into the arguments the search reads.
    double binning = 0.0;
    auto binSlabItems = [&](const BinSlab& slab) {
        const double b0 = now();
        binItems(sphereBins, BINNED_SPHERES, ids, nSearched, lanes, slab);
        if (nT) binItems(triBins, BINNED_TRIANGLES, (const bodyID_t*)nullptr, nT, 1u, slab);
        const uint64_t first = slab.firstBin(grid);
        args.sphereBins = BinsView{sphereBins.start.data(), sphereBins.items.data(), first};
        if (nT) args.triangleBins = BinsView{triBins.start.data(), triBins.items.data(), first};
        binning += now() - b0;
    };
    binSlabItems(slabAt(0));
    synchronize(stream);
    binning = now() - t0;  // the first slab's binning and everything before it; later slabs' add theirs

    // 2. Pair search: count, offsets, fill (slab by slab).
    pairOffset.resizeDiscarding(nSearched + 1);
    pairOffset.zeroAsync(stream);
    for (int k = 0; k < slabs; k++) {
        if (k > 0) binSlabItems(slabAt(k));
        if (nSearched && sLanes > 1)
            launch(kPairSearchLanes, blocksFor(laneThreads, THREADS), THREADS, 0, stream, v, args, nSearched, sLanes,
                   searchWideFrom, pairOffset.data(), (const PairOffset*)nullptr, (unsigned int*)nullptr,
                   (bodyID_t*)nullptr);
        else if (nSearched)
            launch(kPairSearch, blocksFor(nSearched, THREADS), THREADS, 0, stream, v, args, dormantBins, ids, nSearched,
                   searchWideFrom, slabAt(k).searched, pairOffset.data(), (const PairOffset*)nullptr,
                   (bodyID_t*)nullptr, (bodyID_t*)nullptr);
    }
    if (nWide)
        launch(kPairSearchWide, blocksFor(wideThreads, THREADS), THREADS, 0, stream, v, args,
               (const bodyID_t*)wideSpheres.data(), nWide, WIDE_SPHERE_LANES, pairOffset.data(),
               (const PairOffset*)nullptr, (unsigned int*)nullptr, (bodyID_t*)nullptr);
    const size_t total = scanPairCounts(nSearched + 1);
    // The outbox is on dT's GPU: size it there (its As once they are made compact, below).
    onDevice(dTDevice, device, [&] { out.geomB.resizeDiscarding(total); });
    KinematicsOutbox& dst = staged ? localOut : out;
    if (staged) localOut.geomB.resizeDiscarding(total);
    // A one thread a sphere searches without the registry is that sphere: the offsets imply every
    // pair's A, which is never written whole. The other searches write it whole first.
    const bool aFromOffsets = !useDormant && sLanes == 1 && nWide == 0;
    if (!aFromOffsets) wholeA.resizeDiscarding(total);
    bodyID_t* aOut = aFromOffsets ? nullptr : wholeA.data();
    if (total && sLanes > 1) {
        // Several threads a sphere fill its partners in no order; then each sphere's into
        // contact-set order.
        laneCursor.resizeDiscarding(nSearched);
        laneCursor.zeroAsync(stream);
        launch(kPairSearchLanes, blocksFor(laneThreads, THREADS), THREADS, 0, stream, v, args, nSearched, sLanes,
               searchWideFrom, (PairOffset*)nullptr, (const PairOffset*)pairOffset.data(), laneCursor.data(),
               dst.geomB.data());
        launch(kPairOrder, blocksFor(nSearched, THREADS), THREADS, 0, stream, v, nSearched, searchWideFrom,
               (const PairOffset*)pairOffset.data(), aOut, dst.geomB.data());
    } else if (total) {
        // Last slab first: its bins are still held from the count (in one slab, the whole grid's);
        // the others' are made again. (Each sphere writes at its own offset: the order is free.)
        for (int k = slabs - 1; k >= 0; k--) {
            if (k < slabs - 1) binSlabItems(slabAt(k));
            launch(kPairSearch, blocksFor(nSearched, THREADS), THREADS, 0, stream, v, args, dormantBins, ids, nSearched,
                   searchWideFrom, slabAt(k).searched, (PairOffset*)nullptr, (const PairOffset*)pairOffset.data(), aOut,
                   dst.geomB.data());
        }
    }
    if (total && nWide) {
        // The wide spheres' lanes fill their partners in no order; then each one's into contact-set
        // order.
        wideCursor.resizeDiscarding(nWide);
        wideCursor.zeroAsync(stream);
        const bodyID_t* wide = wideSpheres.data();
        const PairOffset* offsets = pairOffset.data();
        launch(kPairSearchWide, blocksFor(wideThreads, THREADS), THREADS, 0, stream, v, args, wide, nWide,
               WIDE_SPHERE_LANES, (PairOffset*)nullptr, offsets, wideCursor.data(), dst.geomB.data());
        launch(kPairRankWide, blocksFor(wideThreads, THREADS), THREADS, 0, stream, wide, nWide, WIDE_SPHERE_LANES,
               offsets, aOut, (const bodyID_t*)dst.geomB.data());
        launch(kPairFinishWide, blocksFor(wideThreads, THREADS), THREADS, 0, stream, wide, nWide, WIDE_SPHERE_LANES,
               offsets, aOut, dst.geomB.data());
    }
    // Pairs found from the moving side with a dormant sphere of lower id: into (A, B) order.
    if (useDormant) {
        // (The registry's sort indexes its pairs in 32 bits.)
        requireIndexable(total, "contact pairs found beside dormant spheres", FEWER_PAIRS_REMEDY, CALL);
        dormant.sortPairs(v, aOut, dst.geomB.data(), (unsigned int)total, prim, stream);
    }
    // Between synchronous detections a large scene's bins go (below): here already, before the As are
    // made compact, so that the detection's peak is its fill (the bins and the outbox's Bs beside
    // the offsets), not the bins and the whole outbox (about 9 B/sphere of a slab's bins in the
    // early mixer; a buffer's release waits for the kernels before it).
    const bool releasingScratch = inPlace && scratchBytes() > keepScratchUpTo;
    if (releasingScratch) releaseBins();
    // The As compact (state/CompactPairA.h), from the offsets or from the whole ones. The outbox's
    // are on dT's GPU: where that is another one, made here and copied there.
    if (staged) {
        compactPairAs(pairAKernels, aOut, pairOffset.data(), nSearched, total, localOut.pairA, pairARows, prim, stream);
        onDevice(dTDevice, device, [&] { out.pairA.resizeLike(localOut.pairA, total); });
        out.pairA.copyFromAsync(localOut.pairA, total, stream);
        out.geomB.copyFromAsync(localOut.geomB, total, stream);
    } else {
        compactPairAs(pairAKernels, aOut, pairOffset.data(), nSearched, total, out.pairA, pairARows, prim, stream);
    }
    // Reported only once everything is in the outbox: dT reads it on its own stream, unordered
    // with this one.
    synchronize(stream);
    // Between synchronous detections the steps hold the GPU alone: a large scene's bins and counts
    // go (4 B per sphere each, and per bin), to be made again by the next detection.
    if (releasingScratch) releaseScratch();
    r.binningSeconds = binning;
    r.searchSeconds = now() - t0 - binning;
    r.order = o;
    r.numPairs = total;
    lastPairs = total;
}

CudaKinematics::CudaKinematics(int kTDevice, int dTDevice, const DeviceState& source, Stream dtStream)
    : m_kTDevice(kTDevice), m_dTDevice(dTDevice), m_source(source), m_dtStream(dtStream) {
    // The outbox's pairs become a contact set when dT takes them (their buffers are swapped).
    m_outbox.pairA.setGroup(MemoryGroup::CONTACTS);
    m_outbox.geomB.setGroup(MemoryGroup::CONTACTS);
    m_inbox.setGroup(MemoryGroup::DETECTION);
    m_keepScratchUpTo = keepRebuiltArraysUpTo("Initialize");
    // dT's GPU is current here: the event and the exchange buffers belong to it.
    cudaEvent_t event = nullptr;
    DEME_CUDA_CHECK("Initialize", cudaEventCreateWithFlags(&event, cudaEventDisableTiming));
    m_submitted = event;
    m_thread = std::thread([this] { run(); });
    std::unique_lock<std::mutex> lock(m_startMutex);
    m_startWake.wait(lock, [this] { return m_started; });
    if (m_startFailure) {
        std::exception_ptr f = m_startFailure;
        lock.unlock();
        // The thread has ended (a failed start-up returns); join it before the members go.
        m_thread.join();
        cudaEventDestroy(event);
        m_submitted = nullptr;
        std::rethrow_exception(f);
    }
}

CudaKinematics::~CudaKinematics() {
    m_mailbox.stop();
    if (m_thread.joinable()) m_thread.join();
    if (m_submitted && cudaEventDestroy(static_cast<cudaEvent_t>(m_submitted)) != cudaSuccess) cudaGetLastError();
}

bool CudaKinematics::mayBinSpheresByCentre(size_t spheres) const {
    const size_t most = std::numeric_limits<unsigned int>::max();
    return centreBinning((unsigned int)std::min(spheres, most));
}

void CudaKinematics::setGeometry(const SimState& s, const BinGrid& g, const FamilyRules& families,
                                 const Settings& settings) {
    if (!m_mailbox.idle()) throwError(CALL, "internal: the kinematics geometry changed while an order was in flight");
    Geometry& k = m_geometry;
    // A second GPU needs its own copy of the spheres' owners and radii; dT's GPU has them already.
    const bool staged = m_kTDevice != m_dTDevice;
    k.sphereOwner = staged ? s.spheres.owner : std::vector<bodyID_t>();
    k.radius = staged ? s.spheres.radius : std::vector<float>();
    k.maxRadius = 0.0;
    k.minRadius = s.spheres.radius.empty() ? 0.0 : (double)s.spheres.radius[0];
    k.wideRadius = wideSphereRadius(g);
    k.wideSpheres.clear();
    for (size_t i = 0; i < s.spheres.radius.size(); i++) {
        k.maxRadius = std::max(k.maxRadius, (double)s.spheres.radius[i]);
        k.minRadius = std::min(k.minRadius, (double)s.spheres.radius[i]);
        if (s.spheres.radius[i] >= k.wideRadius) k.wideSpheres.push_back((bodyID_t)i);
    }
    k.anaOwner = s.analytical.owner;
    k.anaType = s.analytical.type;
    k.anaRadius = s.analytical.radius;
    k.anaInside = s.analytical.inside;
    k.triOwner = s.triangles.owner;
    k.familyMask.assign(families.contactMask(), families.contactMask() + NUM_FAMILIES * NUM_FAMILIES);
    k.familyExtraMargin.assign(settings.familyExtraMargin, settings.familyExtraMargin + NUM_FAMILIES);
    // Bin indices are 32-bit keys on the GPU (the CUB sort by bin).
    if (g.numBins() >= (uint64_t(1) << 32))
        throwError("Initialize", "the contact-detection grid has " + std::to_string(g.numBins()) +
                                     " bins, more than the GPU's 32-bit bin keys hold: choose larger bins "
                                     "(SetInitBinSize) or a smaller domain");
    k.grid = g;
    k.frame = s.frame;
    k.dormant = DormantFamilies::of(s, families);
    k.numOwners = (uint32_t)s.owners.size();
    k.numSpheres = (uint32_t)s.spheres.size();
    k.spheresAreOwners = s.spheresAreOwners;
    k.numAnalytical = (uint32_t)s.analytical.size();
    k.numTriangles = (uint32_t)s.triangles.size();
    m_geometryChanged = true;
}

void CudaKinematics::post(const DetectionOrder& order, bool inPlace) {
    if (!m_mailbox.idle()) throwError(CALL, "internal: a kinematics order was sent while another was in flight");
    const Geometry& k = m_geometry;
    KinematicsInbox& in = m_inbox;
    if (inPlace) {
        // The inbox is not read: a large one (an asynchronous call's, before a switch) goes.
        if (in.bytes() > m_keepScratchUpTo) in.release();
    } else {
        // The snapshot, copied on dT's stream (dT's GPU is current for this thread) into the inbox,
        // sized here: a run that only detects in place never holds one. Where spheres are their
        // owners, the owners' compact positions stand for the spheres' centres (state/SphereLayout.h).
        in.resize(k.spheresAreOwners, k.numOwners, k.numSpheres, k.numAnalytical, k.numTriangles);
        if (k.spheresAreOwners) {
            in.voxel.copyFromAsync(m_source.owners.voxel, k.numSpheres, m_dtStream);
            in.subX.copyFromAsync(m_source.owners.subX, k.numSpheres, m_dtStream);
            in.subY.copyFromAsync(m_source.owners.subY, k.numSpheres, m_dtStream);
            in.subZ.copyFromAsync(m_source.owners.subZ, k.numSpheres, m_dtStream);
        } else {
            in.spherePos.copyFromAsync(m_source.cache.spherePos, k.numSpheres, m_dtStream);
        }
        in.triVert.copyFromAsync(m_source.cache.triVert, 3 * (size_t)k.numTriangles, m_dtStream);
        in.analPos.copyFromAsync(m_source.cache.analPos, k.numAnalytical, m_dtStream);
        in.analDir.copyFromAsync(m_source.cache.analDir, k.numAnalytical, m_dtStream);
        in.ownerFamily.copyFromAsync(m_source.owners.family, k.numOwners, m_dtStream);
    }
    // kT starts once dT's stream has passed this point: the copies made, or the steps finished.
    DEME_CUDA_CHECK(CALL, cudaEventRecord(static_cast<cudaEvent_t>(m_submitted), toCuda(m_dtStream)));
    Order o{order, m_geometryChanged, inPlace};
    m_geometryChanged = false;
    m_mailbox.post(o);
}

void CudaKinematics::submit(const DetectionOrder& order) { post(order, false); }

bool CudaKinematics::tryTake(DetectionReport& report) { return m_mailbox.tryTake(report); }

void CudaKinematics::waitAndTake(DetectionReport& report) { m_mailbox.waitAndTake(report); }

// dT waits here, so nothing changes its state until the result is back: on one GPU kT reads it
// where it is. (On a second GPU kT copies it over from the inbox, as for an asynchronous order.)
void CudaKinematics::detectNow(const DetectionOrder& order, DetectionReport& report) {
    post(order, detectsInPlace());
    waitAndTake(report);
}

void CudaKinematics::run() {
    std::unique_ptr<Work> w;
    auto reportStart = [this](std::exception_ptr failure) {
        {
            std::lock_guard<std::mutex> lock(m_startMutex);
            m_startFailure = failure;
            m_started = true;
        }
        m_startWake.notify_all();
    };
    // Everything kT allocates for itself is detection's (the outbox was given its group above).
    const MemoryGroupScope group(MemoryGroup::DETECTION);
    try {
        // Every CUDA call of this thread is for kT's GPU unless it says otherwise.
        const DeviceInfo& info = useDevice("Initialize", m_kTDevice);
        w.reset(new Work());
        w->device = m_kTDevice;
        w->dTDevice = m_dTDevice;
        w->staged = m_kTDevice != m_dTDevice;
        w->shared = &m_source;
        cudaStream_t stream = nullptr;
        // Non-blocking: no implicit synchronisation with the legacy default stream, so kT's work
        // overlaps dT's on a shared GPU.
        DEME_CUDA_CHECK("Initialize", cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
        w->stream = stream;
        if (w->staged) {
            // Peer access makes the snapshot and result transfers direct GPU-to-GPU copies; without
            // it the runtime stages them through the host, slower but equally correct.
            int can = 0;
            DEME_CUDA_CHECK("Initialize", cudaDeviceCanAccessPeer(&can, m_kTDevice, m_dTDevice));
            if (can) {
                const cudaError_t e = cudaDeviceEnablePeerAccess(m_dTDevice, 0);
                if (e == cudaErrorPeerAccessAlreadyEnabled)
                    cudaGetLastError();
                else
                    DEME_CUDA_CHECK("Initialize", e);
            }
            m_peerAccess = can != 0;
        }
        CudaCompileOptions opt;
        opt.architecture = info.architecture();
        const std::string path = "backend/cuda/kernels/Detection.cu";
        const CudaCompileResult c = compileCudaSource("Initialize", path, embeddedKernelText(path), opt);
        // A module is loaded per GPU: this one is kT's.
        w->module = CudaModule("Initialize", c.image);
        w->kTriBoxes = w->module.kernel("deme_triangle_boxes");
        w->kBinCount = w->module.kernel("deme_bin_count");
        w->kBinScatter = w->module.kernel("deme_bin_scatter");
        w->kBinSort = w->module.kernel("deme_bin_sort");
        w->kPairSearch = w->module.kernel("deme_pair_search");
        w->kPairSearchLanes = w->module.kernel("deme_pair_search_lanes");
        w->kPairOrder = w->module.kernel("deme_pair_order");
        w->kPairSearchWide = w->module.kernel("deme_pair_search_wide");
        w->kPairRankWide = w->module.kernel("deme_pair_rank_wide");
        w->kPairFinishWide = w->module.kernel("deme_pair_finish_wide");
        w->pairAKernels.load(w->module);
        w->dormant.loadKernels(w->module);
        m_deviceName = info.name;
        m_compileSeconds = c.compileSeconds;
        m_fromCache = c.cacheHit;
    } catch (...) {
        w.reset();  // frees on this thread, with kT's GPU current
        reportStart(std::current_exception());
        return;
    }
    reportStart(nullptr);
    Order order;
    while (m_mailbox.waitForOrder(order)) {
        DetectionReport report;
        try {
            // m_geometry, the inbox and the outbox are kT's to read and write until it reports.
            if (order.geometryChanged) w->upload(m_geometry);
            w->detect(order.order, order.inPlace, m_keepScratchUpTo, m_submitted, m_inbox, m_outbox, report);
            m_dormantRebuilds = w->dormant.rebuilds();
        } catch (...) {
            m_mailbox.fail(std::current_exception());
            continue;
        }
        m_mailbox.deliver(report);
    }
    // kT's buffers, module and stream go here, with kT's GPU current.
    w.reset();
}

}  // namespace deme::cuda
