// The GPU's pooled form of the contact history (docs/memory.md, "History only for the pairs that
// touch (GPU)"): where few pairs of a set have a history (a set within the margin is mostly pairs
// apart, whose history is zeros), each pair keeps a 4-byte slot and only the pairs with a history
// keep W floats, in a pool. A pair that takes a history during the steps claims the pool's next
// slot (claimHistorySlot); where the pool is full, the pair is left pending, the step stops before
// its integration, the host grows the pool and the pending pairs' histories are made again from
// the unchanged state (dynamics/PooledContactStep.h). Plain data, compiled by NVRTC too.
#pragma once

#include <deme/HostDevice.h>
#include <deme/VariableTypes.h>

#include "state/HistorySlot.h"

namespace deme {

// The longest history the pooled form holds (floats per pair; the kernels keep one in registers).
constexpr unsigned int MAX_POOLED_HISTORY = 8;

// A pending pair's slot: the slot it claimed beyond the pool's capacity, with this bit.
constexpr uint32_t PENDING_HISTORY_SLOT = 0x80000000u;

// The pool's counters in device memory, read back by the host after every batch.
struct HistoryPoolControl {
    uint32_t used;     // slots claimed; beyond the capacity the pairs are pending
    uint32_t paused;   // 1: a force pass left pairs pending (the step stops before integration)
    uint32_t filling;  // 1: the pooled force pass makes the pending pairs' histories, and nothing else
    uint32_t spare;
};

// The form's arrays as the kernels see them; `slot` null: the set keeps W floats per pair (the
// dense form, ContactView::wildcards). In the pooled form the per-contact forces of a storing step
// are kept per slot (a pair without a slot exerts nothing).
struct HistoryPoolView {
    uint32_t* slot = nullptr;  // per pair: its slot, NO_HISTORY_SLOT, or a pending slot | PENDING_HISTORY_SLOT
    float* pool = nullptr;     // W floats per slot
    HistoryPoolControl* control = nullptr;
    uint32_t capacity = 0;  // slots the pool holds
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

// A contact's history where the pool keeps it (every sphere-triangle pair has a slot there).
struct HistoryInPool {
    const uint32_t* slot;
    float* pool;
    unsigned int W;
    DEME_HD_INLINE float* operator()(size_t i) const { return pool + (size_t)slot[i] * W; }
};

}  // namespace deme
