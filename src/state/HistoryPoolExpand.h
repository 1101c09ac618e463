// A pooled history (state/HistoryPool.h) as the host keeps a contact set: W floats per pair (zeros
// for a pair without a slot), and per-pair forces from forces kept per slot (a pair without a slot
// exerts nothing).
#pragma once

#include <cstddef>
#include <cstdint>

#include <deme/VariableTypes.h>

#include "state/HistoryPool.h"

namespace deme {

inline void expandPooledHistory(const uint32_t* slots, size_t n, const float* pool, unsigned int W, float* out) {
    for (size_t i = 0; i < n; i++) {
        const uint32_t k = slots[i];
        for (unsigned int w = 0; w < W; w++) out[i * W + w] = k == NO_HISTORY_SLOT ? 0.f : pool[(size_t)k * W + w];
    }
}

inline void expandPooledForces(const uint32_t* slots, size_t n, const float3* perSlot, float3* out) {
    for (size_t i = 0; i < n; i++) out[i] = slots[i] == NO_HISTORY_SLOT ? float3{0.f, 0.f, 0.f} : perSlot[slots[i]];
}

}  // namespace deme
