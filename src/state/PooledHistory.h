// The CPU's contact history kept only for the pairs that have some (docs/memory.md). A contact set
// within the safety margin holds many pairs that do not touch (the early mixer: six per sphere, all
// apart), and a built-in model's history of such a pair is all zeros. So while the CPU steps, a set
// may keep a 4-byte slot per pair instead of its W floats, and the floats of the pairs with a
// history in a pool: NO_HISTORY_SLOT reads as zeros. A pair that starts to touch takes a slot at
// the end of the force pass that gave it a history (pending, below), and keeps it, zeros or not,
// until the next installation, which keeps only the slots with a history left.
//
// This form lives only inside the CPU backend's steps: contacts.wildcards (W floats per pair) is
// the history wherever it is not empty, and every host reader of the contact set gets it there
// (Simulation::stateWithContacts densifies, backend/cpu/HistoryForm.h), so checkpoints, edits,
// contact files and the GPU know only that form.
#pragma once

#include <vector>

#include "state/HistorySlot.h"

namespace deme {

// Pending lists over this many bytes are let go after their pass (kept below: no new pages a step).
constexpr size_t PENDING_HISTORY_KEPT_UP_TO = 32u << 20;

struct PooledHistory {
    std::vector<uint32_t> slot;  // per pair: its slot in `values`, or NO_HISTORY_SLOT (all zeros)
    std::vector<float> values;   // W floats per slot
    // Pairs of the last force pass that took a history without having a slot, per thread of the
    // pass: their indices and W floats each, given slots once the pass is done (the pool is not
    // grown while threads read it).
    std::vector<std::vector<uint32_t>> pendingPair;
    std::vector<std::vector<float>> pendingValues;

    void release() { *this = PooledHistory(); }

    // Before a force pass: one pending list per thread, emptied ...
    void preparePending(int threads) {
        if (pendingPair.size() < (size_t)threads) {
            pendingPair.resize(threads);
            pendingValues.resize(threads);
        }
        for (std::vector<uint32_t>& v : pendingPair) v.clear();
        for (std::vector<float>& v : pendingValues) v.clear();
    }
    // ... and after it, their pairs given slots at the pool's end, in thread order. (Inline: the
    // force pass of a model compiled at run time calls it.)
    void commitPending(unsigned int W) {
        size_t pendingBytes = 0;
        for (size_t t = 0; t < pendingPair.size(); t++) {
            const std::vector<uint32_t>& pairs = pendingPair[t];
            for (size_t k = 0; k < pairs.size(); k++) slot[pairs[k]] = (uint32_t)(values.size() / W + k);
            // (appended as a run: the pool grows geometrically as pairs start to touch, step by step)
            values.insert(values.end(), pendingValues[t].begin(), pendingValues[t].end());
            pendingBytes += pairs.capacity() * sizeof(uint32_t) + pendingValues[t].capacity() * sizeof(float);
        }
        // A burst (a bed settling: many pairs touch at once) does not keep its lists' memory.
        if (pendingBytes > PENDING_HISTORY_KEPT_UP_TO) {
            std::vector<std::vector<uint32_t>>().swap(pendingPair);
            std::vector<std::vector<float>>().swap(pendingValues);
        }
    }
    // What it holds (capacities), for the memory table's contacts and history.
    size_t bytes() const {
        size_t b = slot.capacity() * sizeof(uint32_t) + values.capacity() * sizeof(float);
        for (const std::vector<uint32_t>& v : pendingPair) b += v.capacity() * sizeof(uint32_t);
        for (const std::vector<float>& v : pendingValues) b += v.capacity() * sizeof(float);
        return b;
    }
};

}  // namespace deme
