#include "backend/cpu/ForcePass.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <deme/Error.h>

#include "parallel/Parallel.h"
#include "backend/cpu/ContactARuns.h"
#include "backend/cpu/ForcePassLoop.h"
#include "physics/BuiltInForceModels.h"
#include "runtime/MemoryAccounting.h"
#include "state/SphereLayout.h"

namespace deme {

namespace {

PairTable pairTable(const std::vector<float>& table, unsigned int n) { return PairTable{table.data(), n}; }

}  // namespace

ForcePassResult frictionalHertzForcePass(SimState& s, double time, double dt, ForceStore store) {
    const MaterialTables& mt = s.materials;
    const unsigned int n = mt.count;
    const FrictionalHertzModel model{pairTable(mt.mu, n), pairTable(mt.Crr, n), pairTable(mt.E_eff, n),
                                     pairTable(mt.G_eff, n), pairTable(mt.beta_CoR, n)};
    return runForcePass(s, model, time, dt, store);
}

ForcePassResult frictionlessHertzForcePass(SimState& s, double time, double dt, ForceStore store) {
    const MaterialTables& mt = s.materials;
    const FrictionlessHertzModel model{pairTable(mt.E_eff, mt.count), pairTable(mt.beta_CoR, mt.count)};
    return runForcePass(s, model, time, dt, store);
}

namespace {

// DEME_WIDE_REDUCTION_SLOTS=1 takes 4-byte slots for any set (the tests compare the two widths).
bool wideSlotsForced() {
    const char* v = std::getenv("DEME_WIDE_REDUCTION_SLOTS");
    return v && std::strcmp(v, "1") == 0;
}

// Each crossing contact's slot in its block's window (ascending owners), in contact order, into
// `slots` (and a last entry, never used, that the force pass may read past a block's list). The
// other form is let go.
template <class Slot>
void fillOutSlots(SimState& s, const std::vector<std::vector<bodyID_t>>& window, std::vector<Slot>& slots) {
    ContactArrays& c = s.contacts;
    const size_t n = c.size(), nOwners = s.owners.size(), nBlocks = window.size();
    releaseVector(c.outSlot);
    releaseVector(c.outSlotWide);
    slots.resize((size_t)c.blockOutStart[nBlocks] + 1, 0);
#pragma omp parallel for schedule(dynamic, 4) if (n > PARALLEL_MIN_ITEMS)
    for (long k = 0; k < (long)nBlocks; k++) {
        size_t begin, end;
        forcePassBlockRange(c, (size_t)k, nOwners, begin, end);
        const std::vector<bodyID_t>& w = window[k];
        size_t at = c.blockOutStart[k];
        for (size_t i = begin; i < end; i++) {
            const bodyID_t b = contactOwnerB(s, i);
            if (b < nOwners && indexInForcePassBlock(b, (size_t)k) < FORCE_PASS_BLOCK_OWNERS) continue;
            slots[at++] = (Slot)(std::lower_bound(w.begin(), w.end(), b) - w.begin());
        }
    }
}

}  // namespace

void buildOwnerContactIndex(SimState& s) {
    ContactArrays& c = s.contacts;
    const size_t n = c.size();
    const size_t nOwners = s.owners.size();
    // A's side: the set is sorted by A, and A is always a sphere, whose owners ascend with their
    // ids (state/SimState.h), so each owner's contacts as A are one run.
    c.ownerAStart.assign(nOwners + 1, 0);
    bodyID_t prev = 0;
    for (size_t i = 0; i < n; i++) {
        const bodyID_t o = sphereOwner(s, c.geomA[i]);
        if (o < prev) throwError("contact detection", "internal: the contact set is not sorted by A's owner");
        if (o >= nOwners) throwError("contact detection", "internal: a contact's owner is not in the state");
        prev = o;
        c.ownerAStart[o + 1]++;
    }
    for (size_t o = 0; o < nOwners; o++) c.ownerAStart[o + 1] += c.ownerAStart[o];
    // A as runs where spheres are their owners (backend/cpu/ContactARuns.h): let go before B's side
    // is indexed, which reads B only.
    keepContactAAsRuns(s, true);
    // B's side: per block of A's owners, the distinct owners its contacts have as B outside the
    // block (the block's window, ascending); a B owner inside the block is summed by the block's
    // own thread (most of them: a block is a compact clump of grains), marked in ownerBInBlock.
    const size_t nBlocks = forcePassBlocks(nOwners);
    c.ownerBInBlock.assign((nOwners + 63) / 64, 0);
    std::vector<std::vector<bodyID_t>> window(nBlocks);
    c.blockOutStart.assign(nBlocks + 1, 0);
#pragma omp parallel for schedule(dynamic, 4) if (n > PARALLEL_MIN_ITEMS)
    for (long k = 0; k < (long)nBlocks; k++) {
        size_t begin, end;
        forcePassBlockRange(c, (size_t)k, nOwners, begin, end);
        std::vector<bodyID_t>& w = window[k];
        for (size_t i = begin; i < end; i++) {
            // (A block's owners are whole words of the bits: no two threads write one word.)
            const bodyID_t b = contactOwnerB(s, i);
            if (b < nOwners && indexInForcePassBlock(b, (size_t)k) < FORCE_PASS_BLOCK_OWNERS)
                c.ownerBInBlock[b / 64] |= 1ull << (b % 64);
            else
                w.push_back(b);
        }
        c.blockOutStart[k + 1] = (uint32_t)w.size();  // the block's crossing contacts
        std::sort(w.begin(), w.end());
        w.erase(std::unique(w.begin(), w.end()), w.end());
        w.shrink_to_fit();
    }
    c.blockWindowStart.assign(nBlocks + 1, 0);
    for (size_t k = 0; k < nBlocks; k++) {
        if (!window[k].empty() && window[k].back() >= nOwners)
            throwError("contact detection", "internal: a contact's owner is not in the state");
        c.blockWindowStart[k + 1] = c.blockWindowStart[k] + (uint32_t)window[k].size();
        c.blockOutStart[k + 1] += c.blockOutStart[k];
    }
    const size_t nSlots = c.blockWindowStart[nBlocks];
    // Each crossing contact's slot in its block's window, in contact order: 2 bytes, or 4 where a
    // block's window has more slots than 2 bytes count (a block of 512 owners with over 128
    // distinct B owners outside it each).
    size_t largestWindow = 0;
    for (const std::vector<bodyID_t>& w : window) largestWindow = std::max(largestWindow, w.size());
    if (largestWindow <= 0xFFFFu && !wideSlotsForced())
        fillOutSlots(s, window, c.outSlot);
    else
        fillOutSlots(s, window, c.outSlotWide);
    // Per owner, its slots in block order (a fixed order for its sums). The starts serve as the
    // fill's cursors, each left at the next owner's start and shifted back after (a copy of them
    // would be 4 B per owner more at the index's peak, a detection's).
    c.ownerBStart.assign(nOwners + 1, 0);
    for (const std::vector<bodyID_t>& w : window)
        for (bodyID_t o : w) c.ownerBStart[o + 1]++;
    for (size_t o = 0; o < nOwners; o++) c.ownerBStart[o + 1] += c.ownerBStart[o];
    c.ownerBSlots.resize(nSlots);
    for (size_t k = 0; k < nBlocks; k++)
        for (size_t j = 0; j < window[k].size(); j++)
            c.ownerBSlots[c.ownerBStart[window[k][j]]++] = c.blockWindowStart[k] + (uint32_t)j;
    for (size_t o = nOwners; o > 0; o--) c.ownerBStart[o] = c.ownerBStart[o - 1];
    c.ownerBStart[0] = 0;
    std::vector<std::vector<bodyID_t>>().swap(window);
    c.window.assign(nSlots, WindowLoad{make_float3(0.f), make_float3(0.f)});
}

}  // namespace deme
