// Which form the CPU keeps a contact set's history in while it steps: W floats per pair in
// contacts.wildcards (dense), or a slot per pair and the floats of the pairs that have a history
// (pooled, state/PooledHistory.h). Both give the force model the same values, so a run's
// trajectory is the same bit for bit in either (test ContactHistoryForm.*).
#pragma once

#include <algorithm>
#include <vector>

#include "parallel/Parallel.h"
#include "dynamics/ContactStep.h"
#include "kinematics/HistoryRules.h"
#include "state/SimState.h"

namespace deme {

// Whether a set of `pairs` pairs, `withHistory` of which have a history, is kept pooled: where at
// most half of them have one. Pooled costs 4 + 4 W f bytes a pair with a fraction f of them
// having a history, dense 4 W; below a half the pool is smaller for any W >= 1 even after the
// pairs that start to touch before the next detection, and a settled bed (most pairs touching)
// keeps the dense form, which its steps read in place. DEME_CONTACT_HISTORY=dense or =pooled
// decides for every set (tests, comparisons); another value is a deme::Error.
bool poolsHistory(size_t pairs, size_t withHistory);

// Whether contact i's W floats are a history (not all +0; a -0 is one, so that a pooled pair without
// a slot reads back exactly what the dense form holds). Sphere-triangle pairs always keep a slot:
// the mesh rule hands history between them during the steps (dynamics/MeshContactRule.h).
inline bool pairNeedsHistorySlot(uint8_t type, const float* h, unsigned int W) {
    return type == SPHERE_TRIANGLE || pairCarriesHistory(h, W, 0, 0);
}

// A bit per pair, set where keep(i): the pool's ranked slots (state/PooledHistory.h). Made a word
// (64 pairs) at a time, so no two threads write one.
template <class Keep>
std::vector<uint64_t> pairBits(size_t n, Keep&& keep) {
    std::vector<uint64_t> bits((n + 63) / 64, 0);
#pragma omp parallel for schedule(static) if (n > PARALLEL_MIN_ITEMS)
    for (size_t w = 0; w < bits.size(); w++) {
        uint64_t word = 0;
        for (size_t i = 64 * w; i < std::min(n, 64 * w + 64); i++)
            if (keep(i)) word |= 1ull << (i & 63);
        bits[w] = word;
    }
    return bits;
}

// A set whose history is in `wildcards` moves into the pool where poolsHistory says so: after an
// installation that mapped it dense, and before the steps that follow a host reader, an edit or a
// restart (CpuDynamics). A pooled set stays pooled until its installation replaces it.
void chooseHistoryForm(SimState& s);

// The history back into `wildcards` and the pool let go: for every host reader of the contact set
// (Simulation::stateWithContacts, through CpuDynamics::downloadContacts). Returns whether it was
// pooled.
bool densifyHistory(SimState& s);

}  // namespace deme
