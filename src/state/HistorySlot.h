// The slot of a pair without history in the CPU's pooled form (state/PooledHistory.h), apart so
// that the per-pair rules the GPU compiles too (kinematics/HistoryRules.h) can name it.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

constexpr uint32_t NO_HISTORY_SLOT = 0xFFFFFFFFu;

}  // namespace deme
