// The CPU's force pass as a template over the contact force model: every pair of the active-contact
// set takes the per-contact step of dynamics/ContactStep.h (where the rules are); A's owner takes
// its share in the pass itself, B's owner's share is summed per block of owners for the reduction
// (backend/cpu/Integration.cpp); both in a fixed order (bit-identical for any thread count). The
// built-in models (ForcePass.cpp) and the code generated for a user's model at run time
// (forcemodel/CodeGen.cpp) instantiate this same loop, so a model written as a snippet computes bit
// for bit what the same model built into the library does (test ForceModelBitIdentity).
#pragma once

#include <algorithm>
#include <vector>

#include "parallel/Parallel.h"
#include "dynamics/ContactStep.h"
#include "backend/cpu/ForcePassResult.h"
#include "state/SimState.h"

namespace deme {

// One contact of the set (dynamics/ContactStep.h), A sphere `a`: its force on A and torques about
// A's and B's owners, into the chunk's arrays. Instantiated separately for sphere-sphere contacts (most of any
// granular scene) so that the compiler drops the other geometry branches from that path.
// `history`: the pair's W floats (in the set, or the chunk's copy of a pooled history).
template <class Model, bool SphereSphere>
DEME_HD_INLINE bool forcePassContact(SimState& s, const Model& model, size_t i, bodyID_t a, float* history, float time,
                                     float dt, float3& force, float3& torqueA, float3& torqueB) {
    constexpr uint8_t kType = SphereSphere ? (uint8_t)SPHERE_SPHERE : ANY_CONTACT_TYPE;
    bool applied;
    ContactLoad load;
    const bool touching =
        contactStepWithHistory<Model, kType>(s, model, i, contactIdsWithA<kType>(s, i, a), history,
                                             MeshStateAt{s.contacts.meshState.data(), i}, time, dt, applied, load);
    force = applied ? load.force : make_float3(0.f);
    torqueA = applied ? load.torqueA : make_float3(0.f);
    torqueB = applied ? load.torqueB : make_float3(0.f);
    return touching;
}

// Contacts per step of a block's sweep: short enough for their loads to stay in the cache.
constexpr size_t FORCE_PASS_CHUNK = 256;

// A's owners per block of the pass. The blocks are the unit of the threads' work and of B's sums
// (the block's own B owners summed by its thread, a window of slots for the others), and their size
// is fixed, so that the sums are grouped the same way for any thread count. 512 owners of a
// space-filling-curve order are a compact clump of grains: their B owners are mostly their own,
// and the window 0.5-0.75 slots per owner (docs/memory.md). A multiple of 64: a block's owners are
// whole words of ContactArrays::ownerBInBlock.
constexpr size_t FORCE_PASS_BLOCK_OWNERS = 512;
static_assert(FORCE_PASS_BLOCK_OWNERS % 64 == 0, "a block's owners are whole words of the bits");

// Owner o's index in block k: under FORCE_PASS_BLOCK_OWNERS where o is one of the block's owners,
// larger otherwise (an owner below the block wraps). The one test of whether a contact's B owner is
// summed by its block's thread or takes a window slot (the index and the pass alike).
inline size_t indexInForcePassBlock(size_t o, size_t k) { return o - k * FORCE_PASS_BLOCK_OWNERS; }

inline size_t forcePassBlocks(size_t nOwners) {
    return (nOwners + FORCE_PASS_BLOCK_OWNERS - 1) / FORCE_PASS_BLOCK_OWNERS;
}

// The contacts of block k: those whose A owner is in it (the set is sorted by A's owner).
inline void forcePassBlockRange(const ContactArrays& c, size_t k, size_t nOwners, size_t& begin, size_t& end) {
    begin = c.ownerAStart[k * FORCE_PASS_BLOCK_OWNERS];
    end = c.ownerAStart[std::min(nOwners, (k + 1) * FORCE_PASS_BLOCK_OWNERS)];
}

// Thread t's blocks [first, last): about n / T of the contacts, cut at block boundaries. The same
// blocks go to the same thread in every step (and the owners to about the thread that integrates
// them), so that a contact's history and its owners' state stay in that core's cache.
inline void forcePassThreadBlocks(const SimState& s, int t, int T, size_t& first, size_t& last) {
    const ContactArrays& c = s.contacts;
    const size_t n = c.size(), nBlocks = c.blockWindowStart.empty() ? 0 : c.blockWindowStart.size() - 1;
    auto blockAt = [&](size_t k) -> size_t {
        if (k == 0) return 0;
        if (k >= n) return nBlocks;
        return c.pairAOwner(k) / FORCE_PASS_BLOCK_OWNERS;
    };
    size_t begin, end;
    threadRange(n, t, T, begin, end);
    first = blockAt(begin);
    last = t + 1 == T ? nBlocks : blockAt(end);
}

// A chunk's pairs with a force, appended to the thread's list of stored forces: gathered without
// branches in the cache, then copied as two runs.
inline void storeChunkForces(StoredContactForces& st, int thread, size_t b, size_t m, const float3* force) {
    uint32_t index[FORCE_PASS_CHUNK];
    float3 value[FORCE_PASS_CHUNK];
    size_t count = 0;
    for (size_t j = 0; j < m; j++) {
        index[count] = (uint32_t)(b + j);
        value[count] = force[j];
        count += !isZero(force[j]);
    }
    st.index[thread].insert(st.index[thread].end(), index, index + count);
    st.force[thread].insert(st.force[thread].end(), value, value + count);
}

// A chunk's pooled histories (state/PooledHistory.h) copied out for the steps, zeros where a pair
// has no slot ...
template <unsigned int W>
inline void fetchPooledHistory(const PooledHistory& p, size_t b, size_t m, float* history) {
    std::fill(history, history + m * W, 0.f);
    PooledSlotCursor cursor(p, b);
    for (size_t j = 0; j < m; j++)
        if (const uint32_t k = cursor.next(b + j); k != NO_HISTORY_SLOT)
            std::copy(&p.values[(size_t)k * W], &p.values[(size_t)k * W] + W, history + j * W);
}

// ... and back: into the pair's slot, or, for a pair without one that now has a history, into the
// thread's pending list (PooledHistory::commitPending gives it a slot after the pass).
template <unsigned int W>
inline void keepPooledHistory(PooledHistory& p, int thread, size_t b, size_t m, const float* history) {
    PooledSlotCursor cursor(p, b);
    for (size_t j = 0; j < m; j++) {
        const float* h = history + j * W;
        if (const uint32_t k = cursor.next(b + j); k != NO_HISTORY_SLOT) {
            std::copy(h, h + W, &p.values[(size_t)k * W]);
        } else if (!historyIsZero<W>(h)) {
            p.pendingPair[thread].push_back((uint32_t)(b + j));
            p.pendingValues[thread].insert(p.pendingValues[thread].end(), h, h + W);
        }
    }
}

// A chunk's loads onto B's sums: the block's own (B's owner in the block, known by its id) or its
// window's slots (B's owner outside it: the chunk's crossing contacts take the block's list of
// slots in turn from `cursor`), chosen without a branch (the two are mixed). The list has an entry
// past its end, read and not used where the block's last crossing contact is behind.
template <class Slot>
inline void addBShares(const SimState& s, const Slot* outSlot, size_t& cursor, size_t k, size_t b,
                       WindowLoad* blockWindow, WindowLoad* inBlock, const float3* force, const float3* torqueB,
                       size_t m) {
    WindowLoad* const sums[2] = {blockWindow, inBlock};
    for (size_t j = 0; j < m; j++) {
        const size_t inBlockIndex = indexInForcePassBlock(contactOwnerB(s, b + j), k);
        const bool own = inBlockIndex < FORCE_PASS_BLOCK_OWNERS;
        const size_t slot = own ? inBlockIndex : (size_t)outSlot[cursor];
        cursor += !own;
        WindowLoad& sum = sums[own][slot];
        sum.force += force[j];
        sum.negTorque -= torqueB[j];
    }
}

// The block's own B owners' sums onto them, after their A share (0 for an owner that is not A in
// the block), and the sums reset for the next block. The same fixed order for any thread count.
inline void addInBlockSums(const ContactArrays& c, OwnerArrays& ow, size_t k, WindowLoad* inBlock) {
    const size_t base = k * FORCE_PASS_BLOCK_OWNERS;
    const size_t words = std::min(FORCE_PASS_BLOCK_OWNERS / 64, c.ownerBInBlock.size() - base / 64);
    for (size_t w = 0; w < words; w++)
        for (uint64_t bits = c.ownerBInBlock[base / 64 + w]; bits; bits &= bits - 1) {
            const size_t j = w * 64 + (size_t)__builtin_ctzll(bits), o = base + j;
            const bool asA = c.ownerAStart[o + 1] > c.ownerAStart[o];
            ow.contactForce[o] = (asA ? ow.contactForce[o] : make_float3(0.f)) - inBlock[j].force;
            ow.contactTorque[o] = (asA ? ow.contactTorque[o] : make_float3(0.f)) - inBlock[j].negTorque;
            inBlock[j].force = inBlock[j].negTorque = make_float3(0.f);
        }
}

// One force pass. Each block of owners takes its contacts in chunks: the loads of a chunk are
// computed (sphere pairs as one vectorisable sweep), then added in contact order to A's owner and to
// B's sum: the thread's own for a B owner in the block (added to the owner at the block's end), the
// window slot for another. Every owner thus sums its loads in a fixed order (A's contacts, then B's
// in its own block, here; then its slots in block order in the reduction), bit-identical for any
// thread count. A pair whose model exerts nothing adds +0 to its sum, which changes no sum: nor do
// the pairs a wider margin or a different detection frequency brings. `store` says which pairs'
// forces on A it keeps for readers.
template <class Model>
ForcePassResult runForcePass(SimState& s, const Model& model, double time, double dt, ForceStore store) {
    ContactArrays& c = s.contacts;
    OwnerArrays& ow = s.owners;
    const size_t n = c.size(), nOwners = ow.size();
    const bodyID_t sphereIdEnd = s.analyticalIdBase();  // B below it: a sphere pair
    const float t = (float)time, h = (float)dt;
    const int T = n > PARALLEL_MIN_ITEMS ? cpuThreadCount() : 1;
    // The last storing step's forces go as the next step starts (the lists' capacity stays, and
    // the per-pair array while steps keep storing into it).
    StoredContactForces& stored = c.stored;
    stored.clear();
    const bool storePairs = store == ForceStore::PAIRS_WITH_FORCE, storeAll = store == ForceStore::EVERY_PAIR;
    if (storePairs && stored.index.size() < (size_t)T) {
        stored.index.resize(T);
        stored.force.resize(T);
    }
    if (storeAll)
        c.force.resize(n);
    else if (!c.force.empty())
        std::vector<float3>().swap(c.force);
    WindowLoad* window = c.window.data();
    // The history: W floats per pair in the set, or pooled (the chunk works on a copy).
    constexpr unsigned int W = Model::kNumContactWildcards;
    const bool pooled = c.historyPooled(W);
    if (pooled) c.pooled.preparePending(T);
    size_t real = 0, realSS = 0;
#pragma omp parallel num_threads(T) if (T > 1) reduction(+ : real, realSS)
    {
        const int thread = T > 1 ? cpuThreadIndex() : 0;
        float3 chunkForce[FORCE_PASS_CHUNK], torqueA[FORCE_PASS_CHUNK], torqueB[FORCE_PASS_CHUNK];
        bodyID_t chunkOwner[FORCE_PASS_CHUNK];  // each pair's A's owner
        std::vector<float> chunkHistory(pooled ? FORCE_PASS_CHUNK * W : 0);
        // B's sums for the block's own owners (zeros between blocks: each is reset as it is added).
        std::vector<WindowLoad> inBlock(FORCE_PASS_BLOCK_OWNERS, WindowLoad{make_float3(0.f), make_float3(0.f)});
        size_t firstBlock, lastBlock;
        forcePassThreadBlocks(s, thread, T, firstBlock, lastBlock);
        for (size_t k = firstBlock; k < lastBlock; k++) {
            size_t begin, end;
            forcePassBlockRange(c, k, nOwners, begin, end);
            for (uint32_t w = c.blockWindowStart[k]; w < c.blockWindowStart[k + 1]; w++)
                window[w].force = window[w].negTorque = make_float3(0.f);
            size_t crossing = c.blockOutStart[k];  // the next crossing contact's entry in the slots
            bodyID_t owner = 0;
            size_t run = k * FORCE_PASS_BLOCK_OWNERS;  // the owner whose run as A holds the pair
            float3 F = make_float3(0.f), tau = make_float3(0.f);
            for (size_t b = begin; b < end; b += FORCE_PASS_CHUNK) {
                const size_t m = std::min(FORCE_PASS_CHUNK, end - b);
                // A's owner from the runs; A itself too where the set keeps A as runs (spheres
                // that are their owners: backend/cpu/ContactARuns.h).
                for (size_t j = 0; j < m; j++) {
                    while (c.ownerAStart[run + 1] <= b + j) run++;
                    chunkOwner[j] = (bodyID_t)run;
                }
                const bodyID_t* chunkA = c.aAsRuns ? chunkOwner : c.geomA.data() + b;
                float* history = pooled ? chunkHistory.data() : W ? c.wildcards.data() + b * W : nullptr;
                if (pooled) fetchPooledHistory<W>(c.pooled, b, m, history);
                // The forces go straight to the per-pair array where the step keeps every pair's.
                float3* force = storeAll ? c.force.data() + b : chunkForce;
                // Sphere pairs first, as one vectorisable sweep (masked lanes for other types) ...
#pragma omp simd reduction(+ : realSS)
                for (size_t j = 0; j < m; j++)
                    if (c.geomB[b + j] < sphereIdEnd)  // a sphere pair (state/ContactTypeOf.h)
                        realSS +=
                            forcePassContact<Model, true>(s, model, b + j, chunkA[j], W ? history + j * W : nullptr, t,
                                                          h, force[j], torqueA[j], torqueB[j]);
                // ... then the rest ...
                for (size_t j = 0; j < m; j++)
                    if (c.geomB[b + j] >= sphereIdEnd)
                        real +=
                            forcePassContact<Model, false>(s, model, b + j, chunkA[j], W ? history + j * W : nullptr, t,
                                                           h, force[j], torqueA[j], torqueB[j]);
                if (pooled) keepPooledHistory<W>(c.pooled, thread, b, m, history);
                // ... and the loads, in contact order, onto A's owner and B's slot.
                for (size_t j = 0; j < m; j++) {
                    const size_t i = b + j;
                    const bodyID_t o = chunkOwner[j];
                    if (o != owner || i == begin) {
                        if (i != begin) {
                            ow.contactForce[owner] = F;
                            ow.contactTorque[owner] = tau;
                        }
                        owner = o;
                        F = tau = make_float3(0.f);
                    }
                    F += force[j];
                    tau += torqueA[j];
                }
                WindowLoad* const blockWindow = window + c.blockWindowStart[k];
                if (c.outSlotWide.empty())
                    addBShares(s, c.outSlot.data(), crossing, k, b, blockWindow, inBlock.data(), force, torqueB, m);
                else
                    addBShares(s, c.outSlotWide.data(), crossing, k, b, blockWindow, inBlock.data(), force, torqueB, m);
                if (storePairs) storeChunkForces(stored, thread, b, m, force);
            }
            if (end > begin) {
                ow.contactForce[owner] = F;
                ow.contactTorque[owner] = tau;
            }
            addInBlockSums(c, ow, k, inBlock.data());
        }
    }
    if (pooled) c.pooled.commitPending(W);
    return ForcePassResult{real + realSS, realSS};
}

}  // namespace deme
