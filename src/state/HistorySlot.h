// The slot of a pair without history in the CPU's pooled form (state/PooledHistory.h), and what a
// history of zeros is, apart so that the per-pair rules the GPU compiles too
// (kinematics/HistoryRules.h, dynamics/ContactStep.h) can name them.
#pragma once

#include <deme/HostDevice.h>
#include <deme/VariableTypes.h>

namespace deme {

constexpr uint32_t NO_HISTORY_SLOT = 0xFFFFFFFFu;

// Whether a float is +0, bit for bit (a -0 is not).
DEME_HD_INLINE bool isPositiveZero(float v) {
#ifdef __CUDA_ARCH__
    const uint32_t bits = __float_as_uint(v);
#else
    uint32_t bits;
    __builtin_memcpy(&bits, &v, sizeof bits);
#endif
    return bits == 0u;
}

}  // namespace deme
