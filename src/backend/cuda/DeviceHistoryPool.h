// A GPU contact set's pooled history (state/HistoryPool.h); the rule that chooses it is
// runtime/HistoryPoolPolicy.h. CudaDynamics holds one per contact set (CudaHistoryPool.cpp);
// history mapping makes it (DeviceHistoryMapping).
#pragma once

#include <cstdint>

#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/DeviceState.h"
#include "kinematics/HistoryRules.h"
#include "runtime/HistoryPoolPolicy.h"
#include "state/HistoryPool.h"

namespace deme::cuda {

struct DeviceHistoryPool {
    DeviceBuffer<unsigned long long> ranked;     // a bit a pair: a slot given at the installation
    DeviceBuffer<uint32_t> rankBase;             // per 64 pairs (one more: the ranked slots' count)
    DeviceBuffer<unsigned long long> late;       // a bit a pair: a slot given since, in lateTable
    DeviceBuffer<unsigned long long> lateTable;  // lateTableEntriesFor(capacity, rankedSlots) entries
    DeviceBuffer<float> pool;                    // W floats per slot, `capacity` slots
    // The sphere-triangle pairs' mesh states, per ranked slot (rankedSlots of them), where
    // meshStateBySlot; a trimmed set keeps them per pair (DeviceContacts::meshState).
    DeviceBuffer<uint8_t> meshState;
    uint32_t capacity = 0, rankedSlots = 0;
    bool active = false;  // false: the set keeps W floats per pair (its wildcards)
    bool meshStateBySlot = false;

    HistoryPoolView view(HistoryPoolControl* control) {
        if (!active) return HistoryPoolView{};
        HistoryPoolView v;
        v.ranked = (const uint64_t*)ranked.data();
        v.rankBase = rankBase.data();
        v.late = late.data();
        v.lateTable = lateTable.data();
        v.lateMask = (uint32_t)(lateTable.size() - 1);
        v.pool = pool.data();
        v.meshState = meshStateBySlot ? meshState.data() : nullptr;
        v.control = control;
        v.capacity = capacity;
        return v;
    }
    // The slots as history mapping reads an old set's (null ranked where the set is dense); and the
    // set's history as it reads it, `set` the set's per-pair arrays (n pairs).
    RankedSlotsView slots() const {
        RankedSlotsView v;
        if (!active) return v;
        v.ranked = (const uint64_t*)ranked.data();
        v.rankBase = rankBase.data();
        v.late = (const uint64_t*)late.data();
        v.lateTable = lateTable.data();
        v.lateMask = (uint32_t)(lateTable.size() - 1);
        return v;
    }
    OldContactHistory oldHistory(const DeviceContacts& set, size_t n, unsigned int W, const uint8_t* persistent,
                                 const ContactInitRule* rules, unsigned int numRules) const {
        const bool bySlot = active && meshStateBySlot;
        OldContactHistory h{ContactKeys{set.pairA.view(), set.geomB.data(), n},
                            active ? pool.data() : set.wildcards.data(),
                            bySlot ? meshState.data() : set.meshState.data(),
                            persistent,
                            W,
                            rules,
                            numRules,
                            slots()};
        h.meshStateBySlot = bySlot;
        return h;
    }

    void release() {
        ranked.release();
        rankBase.release();
        late.release();
        lateTable.release();
        pool.release();
        meshState.release();
        capacity = rankedSlots = 0;
        active = false;
        meshStateBySlot = false;
    }
};

}  // namespace deme::cuda
