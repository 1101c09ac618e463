#include "backend/cuda/DeviceHistoryMapping.h"

#include <string>
#include <utility>

#include <deme/Error.h>

#include "backend/cuda/EmbeddedKernel.h"
#include "kinematics/CarriedPairsRule.h"
#include "runtime/IndexLimits.h"

namespace deme::cuda {

namespace {

constexpr unsigned int THREADS = 256;
constexpr const char* kSourcePath = "backend/cuda/kernels/HistoryMapping.cu";

ContactKeys keysOf(const DeviceContacts& c, size_t n) { return ContactKeys{c.pairA.view(), c.geomB.data(), n}; }

}  // namespace

void DeviceHistoryMapping::load(const std::string& call, const CudaCompileOptions& options) {
    const CudaCompileResult r = compileCudaSource(call, kSourcePath, embeddedKernelText(kSourcePath), options);
    m_compileSeconds = r.compileSeconds;
    m_fromCache = r.cacheHit;
    m_module = CudaModule(call, r.image);
    m_missing = m_module.kernel("deme_persistent_missing");
    m_merge = m_module.kernel("deme_persistent_merge");
    m_map = m_module.kernel("deme_map_history");
    m_markSlots = m_module.kernel("deme_mark_history_slots");
    m_mapPooled = m_module.kernel("deme_map_history_pooled");
    m_markMesh = m_module.kernel("deme_mark_mesh_pairs");
    m_markCarried = m_module.kernel("deme_mark_carried_pairs");
    m_mapMarked = m_module.kernel("deme_map_marked_history");
    m_markHandedOn = m_module.kernel("deme_mark_pairs_handed_on");
    m_countMarks = m_module.kernel("deme_count_marks");
    m_keepHandedOn = m_module.kernel("deme_keep_pairs_handed_on");
    m_rehashLate = m_module.kernel("deme_rehash_late_slots");
    m_pairAKernels.load(m_module);
    m_pairARows.setGroup(MemoryGroup::CONTACTS);
}

void DeviceHistoryMapping::uploadRules(const std::vector<ContactInitRule>& rules) {
    m_rules.upload(rules);
    m_numRules = (unsigned int)rules.size();
}

bool DeviceHistoryMapping::keepOnlyPairsHandedOn(DeviceContacts& set, DeviceHistoryPool& pool, size_t& n,
                                                 unsigned int W, DevicePrimitives& prim, Stream stream,
                                                 const std::function<void()>& beforeTrim) {
    if (n == 0 || !mayKeepOnlyPairsHandedOn(m_numRules > 0)) return false;
    const MemoryGroupScope group(MemoryGroup::CONTACTS);  // the marks
    const OldContactHistory h =
        pool.oldHistory(set, n, W, set.persistent.empty() ? nullptr : set.persistent.data(), nullptr, 0u);
    // The marks, a bit a pair, and each word's first rank (12 B per 64 pairs beside the whole set:
    // this is the detection's peak, without the outbox that an installation in this mode lets go;
    // kernels/HistoryMapping.cu).
    const size_t numWords = ((size_t)n + 63) / 64;
    DeviceBuffer<unsigned long long> marks(numWords, stream);
    DeviceBuffer<uint32_t> rankBase;
    marks.zeroAsync(stream);
    launch(m_markHandedOn, blocksFor(n, THREADS), THREADS, 0, stream, h, marks.data());
    const uint64_t kept = rankMarks(marks.data(), numWords, rankBase, prim, stream);
    // (Ranks are 32-bit: a set whose pairs to keep pass that is not trimmed, as it would not pay.)
    if (kept > MAX_INDEXED_ITEMS || !keepingOnlyPairsHandedOnPays(n, kept)) return false;
    beforeTrim();
    // The trimmed arrays, of the contact sets' group for good (they become the set's).
    auto sized = [stream](auto& buffer, size_t count) {
        buffer.setGroup(MemoryGroup::CONTACTS);
        buffer.resize(count, stream);
    };
    DeviceBuffer<bodyID_t> a, b;
    DeviceBuffer<uint8_t> meshState, persistent;
    DeviceBuffer<float> wildcards;
    // A pooled set's kept pairs are its late pairs, their slots as they were (the trimmed set serves
    // no step: only the next installation reads it, through slotOf).
    DeviceBuffer<unsigned long long> ranked, late, lateTable;
    DeviceBuffer<uint32_t> keptRankBase;
    const size_t keptWords = ((size_t)kept + 63) / 64;
    sized(a, kept);
    sized(b, kept);
    sized(meshState, kept);
    if (h.persistent) sized(persistent, kept);  // a set without flags keeps none
    if (pool.active) {
        sized(ranked, keptWords);
        sized(keptRankBase, keptWords + 1);
        sized(late, keptWords);
        sized(lateTable, lateTableEntriesFor(kept, 0));
        ranked.zeroAsync(stream);
        keptRankBase.zeroAsync(stream);
        late.zeroAsync(stream);
        lateTable.zeroAsync(stream);
    } else {
        sized(wildcards, (size_t)kept * W);
    }
    if (kept)
        launch(m_keepHandedOn, blocksFor(n, THREADS), THREADS, 0, stream, h, (const unsigned long long*)marks.data(),
               (const uint32_t*)rankBase.data(), a.data(), b.data(), meshState.data(), persistent.data(),
               wildcards.data(), late.data(), lateTable.data(), (uint32_t)(lateTable.size() - 1));
    // The kept As compact (state/CompactPairA.h; waits for the stream, so the whole set's buffers are
    // read: they go as the trimmed ones take their place).
    DevicePairA keptA;
    keptA.setGroup(MemoryGroup::CONTACTS);
    compactPairAs(m_pairAKernels, a.data(), nullptr, 0u, kept, keptA, m_pairARows, prim, stream);
    synchronize(stream);
    std::swap(set.pairA, keptA);
    std::swap(set.geomB, b);
    std::swap(set.meshState, meshState);
    std::swap(set.persistent, persistent);
    if (pool.active) {
        std::swap(pool.ranked, ranked);
        std::swap(pool.rankBase, keptRankBase);
        std::swap(pool.late, late);
        std::swap(pool.lateTable, lateTable);
        pool.rankedSlots = 0;
        pool.meshState.release();  // the kept pairs' mesh states are per pair now
        pool.meshStateBySlot = false;
    } else {
        std::swap(set.wildcards, wildcards);
    }
    n = kept;
    return true;
}

size_t DeviceHistoryMapping::mergePersistent(DeviceContacts& freshSet, size_t nFresh, const DeviceContacts& oldSet,
                                             size_t nOld, DevicePrimitives& prim, Stream stream) {
    m_oldHadPersistent = false;
    if (nOld == 0 || oldSet.persistent.empty()) return nFresh;  // a set without flags has no persistent pair
    const ContactKeys fresh = keysOf(freshSet, nFresh), old = keysOf(oldSet, nOld);
    const uint8_t* persistent = oldSet.persistent.data();
    // Whether the old set has any persistent pair at all (one byte read per pair). Most runs have
    // none: they need no per-pair scratch, which is let go (8 B per pair otherwise).
    m_any.resize(1, stream);
    m_any.zeroAsync(stream);
    launch(m_missing, blocksFor(nOld, THREADS), THREADS, 0, stream, fresh, old, persistent, (unsigned int*)nullptr,
           m_any.data());
    unsigned int any = 0;
    m_any.downloadAsync(&any, 1, stream);
    synchronize(stream);
    m_oldHadPersistent = any != 0;
    if (!any) {
        m_isMissing.release();
        m_missingBefore.release();
        return nFresh;
    }
    m_isMissing.resize((size_t)nOld + 1, stream);
    m_missingBefore.resize((size_t)nOld + 1, stream);
    m_isMissing.zeroAsync(stream);
    launch(m_missing, blocksFor(nOld, THREADS), THREADS, 0, stream, fresh, old, persistent, m_isMissing.data(),
           m_any.data());
    prim.exclusiveSum((const uint64_t*)m_isMissing.data(), (uint64_t*)m_missingBefore.data(), nOld + 1, stream);
    unsigned long long missing = 0;
    m_missingBefore.downloadAsync(&missing, 1, stream, nOld);
    synchronize(stream);
    if (missing == 0) return nFresh;
    const size_t total = nFresh + missing;
    m_mergedA.resize(total, stream);
    m_mergedB.resize(total, stream);
    launch(m_merge, blocksFor((unsigned long long)(nFresh + nOld), THREADS), THREADS, 0, stream, fresh, old,
           (const unsigned long long*)m_isMissing.data(), (const unsigned long long*)m_missingBefore.data(),
           m_mergedA.data(), m_mergedB.data());
    // The merged arrays become the fresh set's (its As compact: state/CompactPairA.h); its former Bs
    // are the next merge's scratch.
    DevicePairA mergedA;
    mergedA.setGroup(MemoryGroup::CONTACTS);
    compactPairAs(m_pairAKernels, m_mergedA.data(), nullptr, 0u, total, mergedA, m_pairARows, prim, stream);
    synchronize(stream);
    m_mergedA.release();  // whole As are scratch only
    std::swap(freshSet.pairA, mergedA);
    std::swap(freshSet.geomB, m_mergedB);
    return total;
}

size_t DeviceHistoryMapping::install(DeviceContacts& fresh, DeviceHistoryPool& freshPool, size_t nFresh,
                                     const DeviceContacts& old, const DeviceHistoryPool& oldPool, size_t nOld,
                                     unsigned int W, const HistoryPoolPolicy& policy, const StateView& view,
                                     DevicePrimitives& prim, Stream stream, uint32_t& slotsUsed) {
    const size_t total = mergePersistent(fresh, nFresh, old, nOld, prim, stream);
    slotsUsed = 0;
    // Flags only where a pair may have one: an old pair had, or the model may set one.
    const bool flags = m_oldHadPersistent || m_modelWritesPersistent;
    if (flags)
        fresh.persistent.resizeDiscarding(total);
    else
        fresh.persistent.release();
    uint8_t* freshPersistent = flags ? fresh.persistent.data() : nullptr;
    freshPool.release();
    // Not the per-contact forces: only the set in use holds them (CudaDynamics::install).
    if (total == 0) {
        fresh.wildcards.resizeDiscarding(0);
        fresh.meshState.resizeDiscarding(0);
        return 0;
    }
    const OldContactHistory history = oldPool.oldHistory(
        old, nOld, W, m_oldHadPersistent ? old.persistent.data() : nullptr, m_rules.data(), m_numRules);
    const ContactKeys keys = keysOf(fresh, total);
    if (policy.considers(total)) {
        // Which pairs keep a slot, a bit each: where no new pair takes an initial value and no old
        // pair is persistent, from the old set's side, else every new pair is searched for
        // (kernels/HistoryMapping.cu). Each marked pair's slot is its rank.
        const bool fromOldSide = m_numRules == 0 && !m_oldHadPersistent;
        const size_t numWords = ((size_t)total + 63) / 64;
        freshPool.ranked.resizeDiscarding(numWords);
        freshPool.ranked.zeroAsync(stream);
        unsigned long long* marks = freshPool.ranked.data();
        if (fromOldSide) {
            launch(m_markMesh, blocksFor(total, THREADS), THREADS, 0, stream, view, keys, marks);
            if (nOld) launch(m_markCarried, blocksFor(nOld, THREADS), THREADS, 0, stream, keys, history, marks);
        } else {
            launch(m_markSlots, blocksFor(total, THREADS), THREADS, 0, stream, view, keys, history, marks);
        }
        // (A count past 2^32 wrapped the ranks; it would need more slots than a pool holds, below.)
        const uint64_t withSlot = rankMarkedPairs(freshPool, prim, stream);
        if (policy.chooses(total, withSlot)) {
            const size_t capacity = policy.capacityFor(withSlot, total);
            if (capacity >= HISTORY_SLOT_LIMIT)
                throwError("DoDynamics", "a contact set of " + std::to_string(total) + " pairs needs " +
                                             std::to_string(capacity) + " history slots; a pool holds at most " +
                                             std::to_string(HISTORY_SLOT_LIMIT - 1));
            fresh.wildcards.release();
            fresh.meshState.release();  // per ranked slot
            freshPool.meshState.resizeDiscarding(withSlot);
            freshPool.meshStateBySlot = true;
            freshPool.pool.resizeDiscarding(capacity * W);
            freshPool.capacity = (uint32_t)capacity;
            freshPool.rankedSlots = (uint32_t)withSlot;
            freshPool.late.resizeDiscarding(freshPool.ranked.size());
            freshPool.late.zeroAsync(stream);
            freshPool.lateTable.resizeDiscarding(lateTableEntriesFor(capacity, withSlot));
            freshPool.lateTable.zeroAsync(stream);
            freshPool.active = true;
            launch(fromOldSide ? m_mapMarked : m_mapPooled, blocksFor(total, THREADS), THREADS, 0, stream, view, keys,
                   history, (const uint64_t*)freshPool.ranked.data(), (const uint32_t*)freshPool.rankBase.data(),
                   freshPool.pool.data(), freshPool.meshState.data(), freshPersistent);
            slotsUsed = (uint32_t)withSlot;
            return total;
        }
        freshPool.release();
    }
    fresh.wildcards.resizeDiscarding((size_t)total * W);
    fresh.meshState.resizeDiscarding(total);
    launch(m_map, blocksFor(total, THREADS), THREADS, 0, stream, view, keys, history, fresh.wildcards.data(),
           fresh.meshState.data(), freshPersistent);
    return total;
}

uint64_t DeviceHistoryMapping::rankMarkedPairs(DeviceHistoryPool& pool, DevicePrimitives& prim, Stream stream) {
    return rankMarks(pool.ranked.data(), pool.ranked.size(), pool.rankBase, prim, stream);
}

uint64_t DeviceHistoryMapping::rankMarks(const unsigned long long* marks, size_t numWords,
                                         DeviceBuffer<uint32_t>& rankBase, DevicePrimitives& prim, Stream stream) {
    rankBase.resizeDiscarding(numWords + 1);
    launch(m_countMarks, blocksFor(numWords + 1, THREADS), THREADS, 0, stream, marks, (unsigned int)numWords,
           rankBase.data());
    // The count in 64 bits first: the ranks' 32-bit sum wraps past 2^32 marks (a set of more pairs).
    m_marked.resize(1, stream);
    prim.sum(rankBase.data(), m_marked.data(), numWords + 1, stream);
    prim.exclusiveSum(rankBase.data(), rankBase.data(), numWords + 1, stream);
    uint64_t marked = 0;
    m_marked.downloadAsync(&marked, 1, stream);
    synchronize(stream);
    return marked;
}

void DeviceHistoryMapping::fitLateTable(DeviceHistoryPool& pool, Stream stream) {
    const size_t entries = lateTableEntriesFor(pool.capacity, pool.rankedSlots);
    if (entries <= pool.lateTable.size()) return;
    DeviceBuffer<unsigned long long> table;
    table.setGroup(MemoryGroup::CONTACTS);
    table.resize(entries, stream);
    table.zeroAsync(stream);
    const size_t oldEntries = pool.lateTable.size();
    launch(m_rehashLate, blocksFor(oldEntries, THREADS), THREADS, 0, stream,
           (const unsigned long long*)pool.lateTable.data(), (unsigned int)oldEntries, table.data(),
           (uint32_t)(entries - 1));
    synchronize(stream);  // the old table is read before it goes
    std::swap(pool.lateTable, table);
}

}  // namespace deme::cuda
