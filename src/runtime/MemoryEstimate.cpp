#include "runtime/MemoryEstimate.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <type_traits>

#include <deme/Error.h>

#include "dynamics/StepBatch.h"
#include "kinematics/DetectionRules.h"
#include "runtime/DetectionSlabs.h"
#include "runtime/EnvironmentCount.h"
#include "runtime/HistoryPoolPolicy.h"
#include "runtime/MemoryAccounting.h"
#include "state/CompactPairA.h"
#include "state/FamilyStepMotion.h"

namespace deme {

namespace {

template <class V>
constexpr size_t elementBytes(const V&) {
    return sizeof(typename std::remove_reference_t<V>::value_type);
}

// The bytes a backend's copy of a field group holds: the host arrays' sizes (they are the scene's,
// assembled by Initialize), the fields of the roles that backend keeps; the results one per owner
// (the backend makes them: state/SimState.h).
struct SizedBytes {
    size_t& sum;
    bool deviceCopy;  // the GPU keeps no HOST-role field
    size_t owners;
    template <class V>
    void operator()(const V& v, const V&, FieldRole role) const {
        if (deviceCopy && role == FieldRole::HOST) return;
        sum += (role == FieldRole::RESULT ? owners : v.size()) * elementBytes(v);
    }
};

// Contact pairs: the bytes one pair takes in one contact set (W wildcard floats), the CPU's
// bookkeeping included where `host`. Not the per-contact force: the GPU keeps it in the idle set's
// memory (contactSetBytes), the CPU only for the pairs with a force, at the end of a call.
size_t bytesPerPair(const ContactArrays& c, unsigned int W, bool host, bool persistentFlags) {
    const void* notPerPair[] = {
        &c.force,       &c.meshContacts, &c.meshContactGroups, &c.ownerAStart,   &c.blockWindowStart, &c.window,
        &c.ownerBStart, &c.ownerBSlots,  &c.ownerBInBlock,     &c.blockOutStart, &c.outSlot,          &c.outSlotWide};
    size_t b = 0;
    forEachContactField(c, c, [&](const auto& v, const auto&, FieldRole role) {
        const void* f = &v;
        const bool perPair = std::find(std::begin(notPerPair), std::end(notPerPair), f) == std::end(notPerPair);
        if (f == &c.wildcards) b += W * elementBytes(v);
        else if (!perPair || (f == &c.persistent && !persistentFlags))
            return;  // per owner, per block, per slot, per mesh contact or per pair with a force; flags not kept
        else if (role != FieldRole::HOST || host) b += elementBytes(v);
    });
    return b;
}

// A GPU set's As (state/CompactPairA.h): a byte a pair and a 4-byte base per 32 pairs. (Blocks kept
// whole in the side table are not counted: a block spans more than a byte of spheres only across a
// run of spheres without pairs, which a packing has few of.)
size_t compactABytes(size_t pairs) { return pairs + pairABlocks(pairs) * sizeof(uint32_t); }
// A pair's bytes in a GPU set but its A (compactABytes): B, the history (dense) and mesh state, the
// flag where kept.
size_t gpuPairBytesBesidesA(const SimState& s, unsigned int W, const ContactSetForm& form) {
    return bytesPerPair(s.contacts, W, false, form.persistentFlags) - sizeof(bodyID_t);
}
// The same in a GPU set that pools its history: no W floats and no mesh state (kept per ranked slot:
// state/HistoryPool.h); its slot is pooledSlotBytes'.
size_t pooledPairBytes(const SimState& s, unsigned int W, const ContactSetForm& form) {
    return gpuPairBytesBesidesA(s, W, form) - 4 * (size_t)W - sizeof(s.contacts.meshState[0]);
}
// The slots of a pooled GPU set of `pairs` pairs: a ranked bit and a late bit a pair and each 64
// pairs' first rank, 20 B per 64 pairs.
size_t pooledSlotBytes(size_t pairs) { return (pairs + 63) / 64 * 20; }
// A late table for `late` late slots (state/HistoryPool.h).
size_t lateTableBytes(size_t late) { return lateTableEntriesFor(late, 0) * sizeof(unsigned long long); }

// What the GPU's trim and installation hold beside the kept pairs where a pooled set is trimmed
// before each synchronous detection (contactSetBytes): the whole set and the trim's marks (a bit a
// pair and each 64 pairs' first rank); 0 where the set is not in that form.
size_t trimmedWholeSetBytes(const SimState& s, size_t pairs, const ContactSetForm& form) {
    const unsigned int W = s.numWildcards;
    const size_t historySlots = form.historySlots;
    if (!form.trimmedBeforeDetection || historySlots == DENSE_HISTORY || W == 0 || 2 * historySlots > pairs) return 0;
    return pairs * pooledPairBytes(s, W, form) + compactABytes(pairs) + pooledSlotBytes(pairs) + (pairs + 63) / 64 * 12;
}

// Detection's bin entries: a box of extent d overlaps on average 1 + d / edge bins along each axis
// (a sphere's is 2r; a triangle's is taken in its owner's frame).
double binsOverlapped(const BinGrid& g, double dx, double dy, double dz) {
    return (1.0 + dx / g.edge.x) * (1.0 + dy / g.edge.y) * (1.0 + dz / g.edge.z);
}
double expectedSphereEntries(const SimState& s, const BinGrid& g) {
    double sum = 0.0;
    for (float r : s.spheres.radius) sum += binsOverlapped(g, 2.0 * r, 2.0 * r, 2.0 * r);
    return sum;
}
double expectedTriangleEntries(const SimState& s, const BinGrid& g) {
    const TriangleArrays& t = s.triangles;
    double sum = 0.0;
    for (size_t i = 0; i < t.size(); i++) {
        const float3 a = t.v0[i], b = t.v1[i], c = t.v2[i];
        auto extent = [](float p, float q, float r) { return (double)std::max({p, q, r}) - std::min({p, q, r}); };
        sum += binsOverlapped(g, extent(a.x, b.x, c.x), extent(a.y, b.y, c.y), extent(a.z, b.z, c.z));
    }
    return sum;
}

std::string gib(size_t bytes) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.2f GiB", (double)bytes / (1024.0 * 1024.0 * 1024.0));
    return buf;
}

}  // namespace

MemoryEstimate estimateRunMemory(const SimState& s, const BinGrid& grid, bool onGpu, bool mayBinByCentre,
                                 bool snapshotKept, size_t pairs, const std::function<ContactSetForm(size_t)>& formFor,
                                 size_t scratchKeptUpTo) {
    MemoryEstimate e;
    const size_t nO = s.owners.size(), nS = s.spheres.size();
    e.pairs = pairs ? pairs : (size_t)(ESTIMATED_PAIRS_PER_SPHERE * (double)nS);
    if (formFor) e.form = formFor(e.pairs);
    auto& b = e.bytes;
    size_t& owner = b[(int)MemoryGroup::OWNER_STATE];
    size_t& geometry = b[(int)MemoryGroup::GEOMETRY];
    const SizedBytes ownerSum{owner, onGpu, nO}, geometrySum{geometry, onGpu, nO};
    // Owners, mass properties, the integration's per-owner scratch; geometry and its placed poses
    // (the kinematic cache, which Initialize has filled): as ShowMemoryStats groups them.
    forEachOwnerField(s.owners, s.owners, ownerSum);
    forEachMassField(s.massProps, s.massProps, ownerSum);
    forEachScratchField(s.integrationScratch, s.integrationScratch, [&](const auto& v, const auto&, FieldRole) {
        owner += nO * elementBytes(v);
    });
    // Each owner's travel at an asynchronous order's snapshot (while one is in flight).
    if (snapshotKept) owner += sizeof(float) * nO;
    forEachSphereField(s.spheres, s.spheres, geometrySum);
    forEachAnalyticalField(s.analytical, s.analytical, geometrySum);
    forEachTriangleField(s.triangles, s.triangles, geometrySum);
    forEachCacheField(s.cache, s.cache, geometrySum);
    if (!onGpu) {  // the host's id maps and per-owner ranges
        owner += 4 * (s.ownerUserToInternal.size() + s.ownerInternalToUser.size());
        geometry += 4 * (s.ownerSphereStart.size() + s.sphereInternalToUser.size() + s.sphereUserToInternal.size());
    }
    for (const std::vector<float>& w : s.wildcards.owner) b[(int)MemoryGroup::WILDCARDS] += 4 * w.size();
    for (const std::vector<float>& w : s.wildcards.geometry) b[(int)MemoryGroup::WILDCARDS] += 4 * w.size();

    const size_t nT = s.triangles.size();
    const double entries = expectedSphereEntries(s, grid), triEntries = expectedTriangleEntries(s, grid);
    const size_t bins = (size_t)grid.numBins() + 1;
    size_t& contacts = b[(int)MemoryGroup::CONTACTS];
    size_t& detection = b[(int)MemoryGroup::DETECTION];
    // Spheres binned by their centres (kinematics/DetectionRules.h), where the backend does at this
    // size (KinematicsBackend::mayBinSpheresByCentre), are one entry each; the margin, not known
    // here, is taken as nothing.
    const float largest = nS ? *std::max_element(s.spheres.radius.begin(), s.spheres.radius.end()) : 0.f;
    const bool byCentre = mayBinByCentre && centreReachFor(grid, (double)largest) > 0.0;
    if (onGpu) {
        contacts = contactSetBytes(s, true, e.pairs, e.form);
        // kT's snapshot (sphere centres, owner families) where it keeps one, pair offsets; the bins'
        // entries (an item id each) and starts, from the counting sort (backend/cuda/CudaKinematics.cpp,
        // Work::detect; the bins an item covers are computed from its box, not stored). (kT on a
        // second GPU also copies the spheres' owners and radii there, 8 B per sphere not counted.)
        // A detection holds them while it runs, so they count, whether or not it lets them go after.
        // By centres the bins are made in slabs of layers where the whole grid's would pass a bound
        // (runtime/DetectionSlabs.h): one slab's starts and its share of the entries are held at
        // once. Planned here with the largest halo binning by centres allows (a reach of 3/4 of a
        // bin: the margin is not known), so that the slabs counted are never thinner than the run's.
        const int kinds = nT ? 2 : 1;
        const double allEntries = (byCentre ? (double)nS : entries) + (nT ? triEntries : 0.0);
        const double slabReach = 0.75 * grid.edge.z;
        const int slabs = byCentre ? detectionSlabCount(grid, slabReach, kinds, (double)nS, (double)nS) : 1;
        const size_t binBytes = (size_t)slabBinBytes(grid, slabReach, slabs, kinds, allEntries);
        detection = (snapshotKept ? nS * 24 + nO : 0) + nS * sizeof(PairOffset) + binBytes;
        // Triangles, where there are any: their global boxes (2 double3).
        if (nT) detection += nT * 48;
        // The snapshot's triangle vertices and analytical components.
        if (snapshotKept) detection += nT * 72 + s.analytical.size() * 48;
        // A synchronous detection in place runs while the set in use holds only the pairs it kept
        // (trimmed before the detection): its scratch and the outbox's ids (B, and A compact with its
        // rows, which become the fresh set's) are held beside the kept pairs, not beside the whole
        // set that the trim and the installation hold (contacts, above), and a large scratch's bins go
        // before A is made compact, the rest before the installation (CudaKinematics::Work::detect):
        // the detection holds the offsets and B with the bins (the fill), then with A (its
        // compaction). The run's peak is then the larger of the two phases: the detection counts only
        // what it holds beyond the whole set and the trim's marks.
        const size_t wholeSet = trimmedWholeSetBytes(s, e.pairs, e.form);
        if (!snapshotKept && wholeSet && detection > scratchKeptUpTo) {
            const size_t compactA = compactABytes(e.pairs) + pairABlocks(e.pairs) * sizeof(uint32_t);
            const size_t detecting = detection - binBytes + e.pairs * sizeof(bodyID_t) + std::max(binBytes, compactA);
            detection = detecting > wholeSet ? detecting - wholeSet : 0;
        }
        // The table of a batch's prescriptions (a row of families per step, CudaStepBatch.cpp). (The
        // active box's step lists, 16-24 B per owner, exist only while some owner is fixed at rest:
        // CudaStepSubset.cpp; not counted.)
        b[(int)MemoryGroup::STEP_SCRATCH] = MAX_BATCH_STEPS * NUM_FAMILIES * sizeof(FamilyStepMotion);
    } else {
        contacts = contactSetBytes(s, false, e.pairs, e.form);
        // The registry's entries and bins' starts, for spheres and for triangles (whose global
        // boxes, 2 double3, are kept too) (backend/cpu/ContactDetector).
        detection = (size_t)(4.0 * (byCentre ? (double)nS : entries)) + 4 * bins;
        if (nT) detection += nT * 48 + (size_t)(4.0 * triEntries) + 4 * bins;
    }
    return e;
}

size_t contactSetBytes(const SimState& s, bool onGpu, size_t pairs, const ContactSetForm& form) {
    const unsigned int W = s.numWildcards;
    const size_t historySlots = form.historySlots;
    const bool pooled = historySlots != DENSE_HISTORY && W > 0;
    // A pooled set holds no W floats per pair; the pool holds them for its slots.
    const size_t historyPerPair = pooled ? 4 * (size_t)W : 0;
    if (!onGpu) {
        // One set with the crossing pairs' 2-byte slots; per owner its two starts, its bit of
        // ownerBInBlock and its window slots (a force, a torque and the owner's entry each;
        // backend/cpu/ForcePassLoop.h). Pooled (state/PooledHistory.h): a bit per pair and a
        // 4-byte base per 64 pairs, and the pool.
        const size_t slots = (size_t)(ESTIMATED_WINDOW_SLOTS_PER_OWNER * (double)s.owners.size());
        const size_t crossing = (size_t)(ESTIMATED_CROSSING_PAIR_SHARE * (double)pairs);
        const size_t pool = pooled ? (pairs + 63) / 64 * 12 + historySlots * 4 * (size_t)W : 0;
        // A scene without triangles keeps no mesh state (backend/cpu/HistoryMapping.cpp).
        const size_t meshState = s.triangles.size() == 0 ? sizeof(s.contacts.meshState[0]) : 0;
        return pairs * (bytesPerPair(s.contacts, W, true, form.persistentFlags) - historyPerPair - meshState) + pool +
               crossing * sizeof(uint16_t) + 8 * (s.owners.size() + 1) + (s.owners.size() + 63) / 64 * 8 +
               slots * (2 * sizeof(float3) + sizeof(uint32_t));
    }
    // Two sets at an installation (the one history mapping reads from and the fresh one, whose
    // pairs were the outbox kT filled); between installations the set in use, the outbox's pairs
    // (the old set's buffers) and the idle set's wildcards, which hold the per-contact forces
    // (grown to hold them where a pair has fewer than three wildcards): at most as much
    // (backend/cuda/CudaContactSets.cpp, DeviceHistoryMapping). Pooled (state/HistoryPool.h):
    // each set's slots (pooledSlotBytes), and at an installation the old pool and the fresh one,
    // each with its late table and a mesh state per slot; the forces are kept per slot.
    const size_t forceBytes = sizeof(float3), idleWildcardBytes = 4 * (size_t)W;
    if (pooled) {
        const size_t perPair = pooledPairBytes(s, W, form);
        const size_t meshState = sizeof(s.contacts.meshState[0]);
        const size_t pools =
            historySlots * (2 * (4 * (size_t)W + meshState) + forceBytes) + 2 * lateTableBytes(form.lateSlots);
        // Trimmed before a synchronous detection (CudaDynamics::beforeDetectNow), where at most half
        // of the pairs have a slot and so at most about half are kept (as late pairs, in a table of
        // their own, with their mesh states per pair): the whole set and the trim's marks (a bit a
        // pair and each 64 pairs' first rank: 12 B per 64 pairs), then an installation's fresh set
        // beside the pairs kept.
        if (const size_t wholeSet = trimmedWholeSetBytes(s, pairs, form))
            return wholeSet + historySlots * (perPair + meshState) + compactABytes(historySlots) +
                   pooledSlotBytes(historySlots) +
                   lateTableBytes(historySlots - std::min(historySlots, form.lateSlots)) + pools;
        return pairs * 2 * perPair + 2 * compactABytes(pairs) + 2 * pooledSlotBytes(pairs) + pools;
    }
    const size_t forceGrowth = forceBytes > idleWildcardBytes ? forceBytes - idleWildcardBytes : 0;
    return pairs * (2 * gpuPairBytesBesidesA(s, W, form) + forceGrowth) + 2 * compactABytes(pairs);
}

size_t memoryLimit(size_t available, const char* call) {
    size_t v = 0;
    if (!environmentCount("DEME_MEMORY_LIMIT", call, "a number of bytes", v)) return available;
    return available == 0 || v < available ? v : available;
}

void requireMemoryFor(const MemoryEstimate& e, size_t available, const std::string& where, const char* call) {
    available = memoryLimit(available, call);
    if (available == 0 || e.total() <= available) return;  // 0: not known
    std::ostringstream msg;
    msg << "the scene needs about " << e.total() << " bytes (" << gib(e.total()) << ") of " << where << " and "
        << available << " (" << gib(available) << ") are available: ";
    bool first = true;
    for (int g = 0; g < NUM_MEMORY_GROUPS; g++) {
        if (!e.bytes[g]) continue;
        msg << (first ? "" : ", ") << memoryGroupName((MemoryGroup)g) << " " << gib(e.bytes[g]);
        first = false;
    }
    msg << ", with " << e.pairs << " contact pairs assumed (" << ESTIMATED_PAIRS_PER_SPHERE << " per sphere)";
    if (e.form.historySlots != DENSE_HISTORY) msg << " and their history pooled in " << e.form.historySlots << " slots";
    if (e.form.trimmedBeforeDetection) msg << ", trimmed to the pairs that hand something on before each detection";
    msg << "; use fewer or larger grains, or a device with more memory";
    throwError(call, msg.str());
}

void requireRoomForContactSet(size_t pairs, size_t needed, const size_t held[NUM_MEMORY_GROUPS],
                              const std::function<size_t()>& freeNow, const std::string& where, const char* call) {
    const size_t heldContacts = held[(int)MemoryGroup::CONTACTS];
    if (needed <= heldContacts) return;  // the set fits what the run holds for contacts already
    size_t heldTotal = 0;
    for (int g = 0; g < NUM_MEMORY_GROUPS; g++) heldTotal += held[g];
    const size_t free = freeNow();
    const size_t capacity = memoryLimit(free ? heldTotal + free : 0, call);
    const size_t projected = heldTotal - heldContacts + needed;
    if (capacity == 0 || projected <= capacity) return;  // 0: not known
    std::ostringstream msg;
    msg << "the contact set has grown to " << pairs << " pairs, which need about " << needed << " bytes ("
        << gib(needed) << ") of " << where << " for contacts and history; the run would then hold " << projected
        << " bytes (" << gib(projected) << ") of the " << capacity << " (" << gib(capacity)
        << ") available (it holds " << heldTotal << " now, " << heldContacts
        << " of them contacts and history). The state is that of the last step that ran, and "
           "WriteCheckpoint saves it; use a smaller margin (SetMaxVelocity, SetExpandSafetyMultiplier, "
           "SetExpandSafetyAdder), fewer or larger grains, or a device with more memory";
    throwError(call, msg.str());
}

size_t hostMemoryAvailable() {
    std::ifstream in("/proc/meminfo");
    std::string line;
    unsigned long long kib = 0;
    while (std::getline(in, line))
        if (std::sscanf(line.c_str(), "MemAvailable: %llu kB", &kib) == 1) return (size_t)kib * 1024;
    return 0;
}

}  // namespace deme
