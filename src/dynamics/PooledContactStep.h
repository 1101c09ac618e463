// The per-contact step where the set keeps its history pooled (state/HistoryPool.h): the GPU's
// force pass for large sets of mostly apart pairs. A pair with a slot works on its W floats in the
// pool; a pair without one starts from zeros (what it has), and where the step leaves it a history
// or a load it claims the pool's next slot and enters the late table. Where the pool is full the
// pair records nothing: its load has been added like any other's, but its history has nowhere to
// go. The step then stops before integration (the integration kernels see
// HistoryPoolControl::paused), the host grows the pool, sets the counter back to the old capacity
// (the claims past it were not kept), and fillPendingHistory makes the histories of the pairs that
// still have no slot again: from zeros, on the same state and clock, so to the bit what the pass
// made (the model reads nothing the pass writes), and exactly those pairs need one. The rest of the
// step then runs as it would have. Only models that write nothing but the pair's history and loads
// take this form (the built-in ones; CudaDynamics chooses).
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

// Where pair i, its step made from zeros (`h`, its load), needs a slot: claims one and puts the
// history (and its force, in a storing step) there; where the pool is full, pauses the step.
template <unsigned int W>
DEME_HD_INLINE void giveHistorySlot(const HistoryPoolView& hp, float3* force, size_t i, const float* h, bool applied,
                                    const ContactLoad& load) {
    if (!needsHistorySlot<W>(h, applied, load)) return;
    const uint32_t k = claimHistorySlot(hp.control);
    if (k >= hp.capacity) {
        hp.control->paused = 1u;
        return;
    }
    storeHistory<W>(h, hp.pool + (size_t)k * W);
    if (force) force[k] = applied ? load.force : make_float3(0.f);
    hp.giveLateSlot(i, k);
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
    const uint32_t slot = hp.slotOf(i);
    if (slot != NO_HISTORY_SLOT) {
        const bool touching = contactStepWithHistory<Model, KnownType>(s, model, i, ids, hp.pool + (size_t)slot * W,
                                                                       hp.meshStateAt(s.contacts.meshState, i, slot),
                                                                       time, dt, applied, load);
        if (force) force[slot] = applied ? load.force : make_float3(0.f);
        return touching;
    }
    float h[W];
    for (unsigned int w = 0; w < W; w++) h[w] = 0.f;
    // A pair without a slot is no sphere-triangle pair (every such pair of a pooled set is ranked):
    // its step is the one without the triangle branch, which would hold registers here (ptxas, sm_90:
    // the pass at its 64-register cap spills 242 bytes this way, 650 with the branch).
    constexpr uint8_t kNoSlotType = KnownType == ANY_CONTACT_TYPE ? NO_TRIANGLE_CONTACT : KnownType;
    const bool touching = contactStepWithHistory<Model, kNoSlotType>(s, model, i, ids, h, MeshStateAt{nullptr, 0}, time,
                                                                     dt, applied, load);
    giveHistorySlot<W>(hp, force, i, h, applied, load);
    return touching;
}

// After a paused pass, the pool grown past every claim and the counter set back to the old
// capacity: pair i's history (and its force, in a storing step) made again where it has no slot and
// needs one, and put in a slot. Nothing else is written: its load is in its owners'.
template <class Model, uint8_t KnownType, class S>
DEME_HD_INLINE void fillPendingHistory(S& s, const Model& model, size_t i, const ContactIds& ids, float time,
                                       float dt) {
    constexpr unsigned int W = Model::kNumContactWildcards;
    const HistoryPoolView& hp = s.historyPool;
    const uint32_t slot = hp.slotOf(i);
    if (slot != NO_HISTORY_SLOT) return;
    float h[W];
    for (unsigned int w = 0; w < W; w++) h[w] = 0.f;
    bool applied = false;
    ContactLoad load;
    constexpr uint8_t kNoSlotType = KnownType == ANY_CONTACT_TYPE ? NO_TRIANGLE_CONTACT : KnownType;
    contactStepWithHistory<Model, kNoSlotType>(s, model, i, ids, h, MeshStateAt{nullptr, 0}, time, dt, applied, load);
    giveHistorySlot<W>(hp, s.contacts.force, i, h, applied, load);
}

}  // namespace deme
