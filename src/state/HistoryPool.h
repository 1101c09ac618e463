// The GPU's pooled form of the contact history (docs/memory.md, "History only for the pairs that
// touch (GPU)"): where few pairs of a set have a history (a set within the margin is mostly pairs
// apart, whose history is zeros), only the pairs with a history keep W floats, in a pool. Which
// pairs have a slot is the CPU's form (state/PooledHistory.h): a bit a pair for the pairs given one
// at the installation, whose slot is their rank among them (12 bytes per 64 pairs), and a second bit
// a pair for the late pairs, those given one since, whose slots are in an open-addressed table
// (state/HistorySlot.h): so a pair without a history looks nothing up, and the set holds about a
// third of a byte a pair for its slots, not a 4-byte index. A pair that takes a history during the
// steps claims the pool's next slot (claimHistorySlot) and enters the table. Where the pool is full
// the pair records nothing, the step stops before its integration, the host grows the pool (and the
// table), and fillPendingHistory makes the histories of the pairs left without a slot again: from
// zeros, on the same state and clock, so to the bit what the pass made (the model reads nothing the
// pass writes). The rest of the step then runs as it would have (dynamics/PooledContactStep.h).
// Plain data, compiled by NVRTC too.
#pragma once

#include <deme/HostDevice.h>
#include <deme/VariableTypes.h>

#include "state/HistorySlot.h"

namespace deme {

// The longest history the pooled form holds (floats per pair; the kernels keep one in registers).
constexpr unsigned int MAX_POOLED_HISTORY = 8;

// A pool holds fewer slots than this, so that the claims of a step past a full pool (one a pair at
// most) cannot wrap the 32-bit counter.
constexpr uint32_t HISTORY_SLOT_LIMIT = 0x80000000u;

// The pool's counters in device memory, read back by the host after every batch.
struct HistoryPoolControl {
    uint32_t used;     // slots claimed; a claim at or beyond the capacity pauses the step
    uint32_t paused;   // 1: a force pass left pairs without the slot they need (the step stops before integration)
    uint32_t filling;  // 1: the pooled force pass makes the histories of those pairs, and nothing else
    uint32_t lost;     // 1: a late pair found the table full (the host keeps it large enough: never)
};

// The form's arrays as the kernels see them; `ranked` null: the set keeps W floats per pair (the
// dense form, ContactView::wildcards). In the pooled form the per-contact forces of a storing step
// are kept per slot (a pair without a slot exerts nothing).
struct HistoryPoolView {
    const uint64_t* ranked = nullptr;    // a bit a pair: a slot given at the installation, its rank
    const uint32_t* rankBase = nullptr;  // per 64 pairs: the ranked slots before them
    unsigned long long* late = nullptr;  // a bit a pair: a slot given since, in the late table
    unsigned long long* lateTable = nullptr;
    uint32_t lateMask = 0;
    float* pool = nullptr;  // W floats per slot
    // The sphere-triangle pairs' mesh states, per ranked slot (every such pair is ranked); null: per
    // pair, in ContactView::meshState (a trimmed set's).
    uint8_t* meshState = nullptr;
    HistoryPoolControl* control = nullptr;
    uint32_t capacity = 0;  // slots the pool holds

    DEME_HD_INLINE RankedSlotsView slots() const {
        RankedSlotsView v;
        v.ranked = ranked;
        v.rankBase = rankBase;
        v.late = (const uint64_t*)late;
        v.lateTable = lateTable;
        v.lateMask = lateMask;
        return v;
    }
    // Pair i's slot, or NO_HISTORY_SLOT (the kernels compile the GPU's lookup only, not the CPU's
    // sorted late pairs that slotOf(slots()) would also hold).
    DEME_HD_INLINE uint32_t slotOf(size_t i) const {
        return rankedOrLateSlot(ranked, rankBase, (const uint64_t*)late, lateTable, lateMask, i);
    }
    // Where pair i's mesh state is, `slot` its slot, `perPair` the set's per-pair states.
    DEME_HD_INLINE MeshStateAt meshStateAt(uint8_t* perPair, size_t i, uint32_t slot) const {
        return meshState ? MeshStateAt{meshState, slot} : MeshStateAt{perPair, i};
    }
    // Pair i takes slot k as a late pair; false where the table is full (flagged for the host).
    DEME_HD_INLINE bool giveLateSlot(size_t i, uint32_t k) const {
        if (!insertLateSlot(lateTable, lateMask, i, k)) {
            control->lost = 1u;
            return false;
        }
        setPairBit(late, i);
        return true;
    }
};

// The next free slot (it may lie beyond the capacity).
DEME_HD_INLINE uint32_t claimHistorySlot(HistoryPoolControl* c) {
#ifdef __CUDA_ARCH__
    return atomicAdd(&c->used, 1u);
#else
    return __atomic_fetch_add(&c->used, 1u, __ATOMIC_RELAXED);
#endif
}

// Whether a force pass of this step left pairs pending (read after the pass has ended).
DEME_HD_INLINE bool historyPoolPaused(const HistoryPoolView& v) {
    return v.control && *static_cast<volatile const uint32_t*>(&v.control->paused) != 0u;
}

// A contact's history where the pool keeps it (every sphere-triangle pair has a slot there), and its
// mesh state: per ranked slot, or per pair where the pool keeps none (perPair).
struct HistoryInPool {
    HistoryPoolView pool;
    uint8_t* perPair;
    unsigned int W;
    DEME_HD_INLINE float* operator()(size_t i) const { return pool.pool + (size_t)pool.slotOf(i) * W; }
    DEME_HD_INLINE uint8_t& meshState(size_t i) const {
        return pool.meshState ? pool.meshState[pool.slotOf(i)] : perPair[i];
    }
};

}  // namespace deme
