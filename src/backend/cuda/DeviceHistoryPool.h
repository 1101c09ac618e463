// A GPU contact set's pooled history (state/HistoryPool.h); the rule that chooses it is
// runtime/HistoryPoolPolicy.h. CudaDynamics holds one per contact set (CudaHistoryPool.cpp);
// history mapping makes it (DeviceHistoryMapping).
#pragma once

#include <cstdint>

#include "backend/cuda/DeviceBuffer.h"
#include "runtime/HistoryPoolPolicy.h"
#include "state/HistoryPool.h"

namespace deme::cuda {

struct DeviceHistoryPool {
    DeviceBuffer<unsigned long long> ranked;     // a bit a pair: a slot given at the installation
    DeviceBuffer<uint32_t> rankBase;             // per 64 pairs (one more: the ranked slots' count)
    DeviceBuffer<unsigned long long> late;       // a bit a pair: a slot given since, in lateTable
    DeviceBuffer<unsigned long long> lateTable;  // lateTableEntriesFor(capacity, rankedSlots) entries
    DeviceBuffer<float> pool;                    // W floats per slot, `capacity` slots
    uint32_t capacity = 0, rankedSlots = 0;
    bool active = false;  // false: the set keeps W floats per pair (its wildcards)

    HistoryPoolView view(HistoryPoolControl* control) {
        if (!active) return HistoryPoolView{};
        HistoryPoolView v;
        v.ranked = (const uint64_t*)ranked.data();
        v.rankBase = rankBase.data();
        v.late = late.data();
        v.lateTable = lateTable.data();
        v.lateMask = (uint32_t)(lateTable.size() - 1);
        v.pool = pool.data();
        v.control = control;
        v.capacity = capacity;
        return v;
    }
    // The slots as history mapping reads an old set's (null ranked where the set is dense).
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

    void release() {
        ranked.release();
        rankBase.release();
        late.release();
        lateTable.release();
        pool.release();
        capacity = rankedSlots = 0;
        active = false;
    }
};

}  // namespace deme::cuda
