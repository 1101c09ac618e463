// The per-contact step where the set keeps its history pooled (state/HistoryPool.h): the GPU's
// force pass for large sets of mostly apart pairs. A pair with a slot works on its W floats in the
// pool; a pair without one starts from zeros (what it has), and where the step leaves it a history
// or a load it claims the pool's next slot. Where the pool is full the pair is left pending: its
// load has been added like any other's, but its history has nowhere to go. The step then stops
// before integration (the integration kernels see HistoryPoolControl::paused), the host grows the
// pool, and fillPendingHistory makes the pending pairs' histories again: from zeros, on the same
// state and clock, so to the bit what the pass made (the model reads nothing the pass writes). The
// rest of the step then runs as it would have. Only models that write nothing but the pair's
// history and loads take this form (the built-in ones; CudaDynamics chooses).
#pragma once

#include "dynamics/ContactStep.h"
#include "state/HistoryPool.h"

namespace deme {

// Whether a step's outcome is worth a slot: a history that is not all +0, or a load of some value.
template <unsigned int W>
DEME_HD_INLINE bool needsHistorySlot(const float* h, bool applied, const ContactLoad& load) {
    if (!historyIsZero<W>(h)) return true;
    return applied && !(isZero(load.force) && isZero(load.torqueA) && isZero(load.torqueB));
}

// Contact i's step in the pooled form (ids read: contactIds). Returns whether the pair touches; the
// force on A goes to contacts.force[slot] where the view asks for it (a storing step).
template <class Model, uint8_t KnownType, class S>
DEME_HD_INLINE bool pooledContactStep(S& s, const Model& model, size_t i, const ContactIds& ids, float time, float dt,
                                      bool& applied, ContactLoad& load) {
    constexpr unsigned int W = Model::kNumContactWildcards;
    static_assert(W > 0 && W <= MAX_POOLED_HISTORY && W <= MAX_COPIED_HISTORY,
                  "the pooled form holds histories of 1 to 8 floats");
    const HistoryPoolView& hp = s.historyPool;
    float3* force = s.contacts.force;
    const uint32_t slot = hp.slot[i];
    if (slot < hp.capacity) {
        const bool touching = contactStepWithHistory<Model, KnownType>(s, model, i, ids, hp.pool + (size_t)slot * W,
                                                                       time, dt, applied, load);
        if (force) force[slot] = applied ? load.force : make_float3(0.f);
        return touching;
    }
    float h[W];
    for (unsigned int w = 0; w < W; w++) h[w] = 0.f;
    const bool touching = contactStepWithHistory<Model, KnownType>(s, model, i, ids, h, time, dt, applied, load);
    if (!needsHistorySlot<W>(h, applied, load)) return touching;
    const uint32_t k = claimHistorySlot(hp.control);
    if (k < hp.capacity) {
        storeHistory<W>(h, hp.pool + (size_t)k * W);
        hp.slot[i] = k;
        if (force) force[k] = applied ? load.force : make_float3(0.f);
    } else {
        hp.slot[i] = k | PENDING_HISTORY_SLOT;
        hp.control->paused = 1u;
    }
    return touching;
}

// After the pool has grown past every claimed slot: pending pair i's history (and its force, in a
// storing step) made again and put in its slot. Nothing else is written: its load is in its owners'.
template <class Model, uint8_t KnownType, class S>
DEME_HD_INLINE void fillPendingHistory(S& s, const Model& model, size_t i, const ContactIds& ids, float time,
                                       float dt) {
    constexpr unsigned int W = Model::kNumContactWildcards;
    const HistoryPoolView& hp = s.historyPool;
    const uint32_t slot = hp.slot[i];
    if (slot == NO_HISTORY_SLOT || !(slot & PENDING_HISTORY_SLOT)) return;
    const uint32_t k = slot & ~PENDING_HISTORY_SLOT;
    float h[W];
    for (unsigned int w = 0; w < W; w++) h[w] = 0.f;
    bool applied = false;
    ContactLoad load;
    contactStepWithHistory<Model, KnownType>(s, model, i, ids, h, time, dt, applied, load);
    storeHistory<W>(h, hp.pool + (size_t)k * W);
    if (s.contacts.force) s.contacts.force[k] = applied ? load.force : make_float3(0.f);
    hp.slot[i] = k;
}

}  // namespace deme
