// Which GPU contact sets keep their history pooled (state/HistoryPool.h, docs/memory.md), and how
// many spare slots a pool is given: the rule CudaDynamics and its history mapping follow, apart
// from the CUDA code so that every build compiles and tests it.
#pragma once

#include <cstddef>

#include "state/HistoryPool.h"

namespace deme {

// Which sets keep their history pooled. DEME_POOLED_HISTORY: "auto" (the default), "1" (every set
// the model allows), "0" (none). DEME_HISTORY_POOL_SPARE: the fewest spare slots a pool is given
// (default 4096; 0 makes the first pair that takes a history in a step pause it, for tests).
struct HistoryPoolPolicy {
    enum class Mode { AUTO, ALWAYS, NEVER };
    Mode mode = Mode::AUTO;
    size_t minSpare = 4096;
    bool modelPools = false;  // the force model has a pooled pass (DeviceForceModel::poolsHistory)
    unsigned int W = 0;

    // A set whose dense history is at most this (bytes) stays dense under AUTO: such a set costs
    // little of a GPU's memory, and the pooled pass of a scene with meshes spills more registers
    // than the dense one (the settled mixer's 4 M pairs, 64 MB of dense history, 8 % slower pooled
    // on one H100; docs/memory.md). The early mixer's 275 M pairs (4.4 GB) ran as fast pooled.
    static constexpr size_t AUTO_MIN_DENSE_BYTES = size_t(256) << 20;

    // From the environment (a value that is neither "auto", "0" nor "1" is a deme::Error).
    static HistoryPoolPolicy fromEnvironment();

    // Whether a set of `pairs` pairs is counted for the pooled form at all.
    bool considers(size_t pairs) const {
        if (!modelPools || W == 0 || W > MAX_POOLED_HISTORY || mode == Mode::NEVER || pairs == 0) return false;
        return mode == Mode::ALWAYS || pairs * W * sizeof(float) > AUTO_MIN_DENSE_BYTES;
    }
    // Whether it is pooled, `withSlot` of its pairs keeping a slot: where they are at most half.
    bool chooses(size_t pairs, size_t withSlot) const { return mode == Mode::ALWAYS || 2 * withSlot <= pairs; }
    // The slots a pool is given where `used` are claimed, in a set of `pairs` pairs: a quarter
    // more, and at least a 64th of the set or minSpare, so that growth is rare.
    size_t capacityFor(size_t used, size_t pairs) const {
        size_t spare = used / 4;
        if (spare < pairs / 64) spare = pairs / 64;
        if (spare < minSpare) spare = minSpare;
        if (minSpare == 0) spare = 0;
        return used + spare;
    }
};

// The entries of a late table (state/HistorySlot.h) for a pool of `capacity` slots of which
// `ranked` are the installation's: a power of two at least twice the late slots the pool can give
// (each a late pair's entry), so that probes stay short and an insertion always finds room.
inline size_t lateTableEntriesFor(size_t capacity, size_t ranked) {
    const size_t late = capacity > ranked ? capacity - ranked : 0;
    size_t entries = 64;
    while (entries < 2 * late) entries *= 2;
    return entries;
}

}  // namespace deme
