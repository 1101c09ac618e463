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
    DeviceBuffer<uint32_t> slot;  // per pair (one more while the set is mapped: the slots' count)
    DeviceBuffer<float> pool;     // W floats per slot, `capacity` slots
    uint32_t capacity = 0;
    bool active = false;  // false: the set keeps W floats per pair (its wildcards)

    void release() {
        slot.release();
        pool.release();
        capacity = 0;
        active = false;
    }
};

}  // namespace deme::cuda
