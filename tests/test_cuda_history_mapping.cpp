// The GPU's history-mapping kernels (src/backend/cuda/kernels/HistoryMapping.cu) checked without a
// GPU: the kernel file is compiled here for the host, each kernel run as a loop over its threads in
// the order DeviceHistoryMapping launches them, and the result compared with the CPU's
// installDetectedContacts (backend/cpu/HistoryMapping.cpp) on random contact sets: the same pairs in
// the same order, the same wildcards (carried over, initial values of new pairs), mesh states and
// persistent flags; and the pooled form's kernels (the GPU's history only for the pairs that have
// one) against the same wildcards, read back per pair. The kernels use nothing of CUDA but the thread index
// (tests/HostKernelEmulation.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "BackendFixture.h"
#include "backend/cpu/CarriedPairs.h"
#include "backend/cpu/HistoryForm.h"
#include "backend/cpu/HistoryMapping.h"
#include "kinematics/CarriedPairsRule.h"
#include "state/HistoryPoolExpand.h"

#include "HostHistoryPool.h"
#include "state/CompactPairAHost.h"

#include "HostKernelEmulation.h"
#include "backend/cuda/kernels/HistoryMapping.cu"
#include "HostKernelEmulationEnd.h"

using namespace deme;

namespace {

struct Pairs {
    std::vector<bodyID_t> a, b;
};

// A new set's marks, a bit a pair, ranked as DeviceHistoryMapping ranks them (deme_count_marks, then
// an exclusive sum of the words' counts); each pair's slot and mesh state (kept per slot) read back.
struct Ranked {
    std::vector<unsigned long long> words;
    std::vector<uint32_t> rankBase;
    size_t n = 0;
    explicit Ranked(size_t pairs) : words((pairs + 63) / 64, 0ull), rankBase((pairs + 63) / 64 + 1, 99u), n(pairs) {}
    // After the mark kernels: the ranks.
    void rank() {
        const size_t numWords = words.size();
        runThreads(numWords + 1, [&] { deme_count_marks(words.data(), (unsigned int)numWords, rankBase.data()); });
        uint32_t sum = 0;
        for (uint32_t& v : rankBase) {
            const uint32_t count = v;
            v = sum;
            sum += count;
        }
    }
    const uint64_t* ranked() const { return (const uint64_t*)words.data(); }
    uint32_t count() const { return rankBase.back(); }
    std::vector<uint32_t> slots() const {
        RankedSlotsView v;
        v.ranked = ranked();
        v.rankBase = rankBase.data();
        std::vector<uint32_t> s(n);
        for (size_t i = 0; i < n; i++) s[i] = slotOf(v, i);
        return s;
    }
    std::vector<uint8_t> meshStates(const std::vector<uint8_t>& perSlot) const {
        const std::vector<uint32_t> s = slots();
        std::vector<uint8_t> m(n, 0);
        for (size_t i = 0; i < n; i++)
            if (s[i] != NO_HISTORY_SLOT) m[i] = perSlot.at(s[i]);
        return m;
    }
};

// `n` distinct sphere pairs (a < b) among `spheres`, sorted by key.
Pairs randomPairs(std::mt19937& rng, unsigned int spheres, size_t n) {
    std::uniform_int_distribution<bodyID_t> pick(0, spheres - 1);
    std::set<std::pair<bodyID_t, bodyID_t>> s;
    while (s.size() < n) {
        bodyID_t x = pick(rng), y = pick(rng);
        if (x != y) s.insert({std::min(x, y), std::max(x, y)});
    }
    Pairs p;
    for (const auto& q : s) p.a.push_back(q.first), p.b.push_back(q.second);
    return p;
}

}  // namespace

TEST(CudaHistoryMapping, KernelsFollowTheCpuRules) {
    std::mt19937 rng(11);
    const unsigned int spheres = 40;
    size_t newPairs = 0;  // pairs new to the set: 0, or 7 between families 0 and 1
    size_t fromOldSide = 0;  // rounds whose pooled mapping was also checked from the old set's side
    for (int round = 0; round < 200; round++) {
        SCOPED_TRACE(round);
        // The CPU's history in either form (backend/cpu/HistoryForm.h), read back densified.
        const deme_test::ScopedEnvironmentVariable form("DEME_CONTACT_HISTORY", round % 2 ? "dense" : "pooled");
        // The CPU's state: spheres in families 0..2, one contact wildcard, a rule for families 0-1.
        SimState s;
        for (unsigned int i = 0; i < spheres; i++) {
            s.spheres.owner.push_back(i);
            s.owners.family.push_back((family_t)(i % 3));
        }
        s.owners.voxel.assign(spheres, 0);  // one owner per sphere (installing a set indexes their contacts)
        // One triangle after the spheres in the id space (no pair names it): a scene with triangles,
        // whose sets keep their mesh state (a scene without keeps none: ContactMeshState.*), carried
        // here for every pair.
        s.triangles.owner.assign(1, 0);
        s.numWildcards = 1;
        s.wildcards.contactInit.push_back({0, 1, 0, 7.f});
        const Pairs old = randomPairs(rng, spheres, std::uniform_int_distribution<size_t>(0, 60)(rng));
        const Pairs fresh = randomPairs(rng, spheres, std::uniform_int_distribution<size_t>(0, 60)(rng));
        const size_t nOld = old.a.size(), nFresh = fresh.a.size();
        std::vector<uint8_t> oldPersistent(nOld);
        // A quarter of the rounds with no persistent pair (the GPU then skips the merge).
        const bool anyAllowed = round % 4 != 0;
        for (auto& p : oldPersistent) p = (uint8_t)(anyAllowed && rng() % 3 == 0);
        ContactArrays& c = s.contacts;
        c.geomA = old.a;
        c.geomB = old.b;
        c.wildcards.resize(nOld);
        for (float& w : c.wildcards) w = (float)(rng() % 1000) + 0.5f;
        c.persistent = oldPersistent;
        c.meshState.resize(nOld);
        for (uint8_t& m : c.meshState) m = (uint8_t)(rng() % 4);
        const std::vector<float> oldWildcards = c.wildcards;
        const std::vector<uint8_t> oldMeshState = c.meshState;
        DetectedContacts detected;
        detected.geomA = fresh.a;
        detected.geomB = fresh.b;
        installDetectedContacts(s, detected, true);  // (the flags kept, to compare)

        // The GPU's steps, as DeviceHistoryMapping runs them.
        // The device's sets keep A compact (state/CompactPairA.h): the kernels read it so here too.
        const HostCompactPairAs freshA = compactPairAsOnHost(fresh.a.data(), nFresh),
                                oldA = compactPairAsOnHost(old.a.data(), nOld);
        const ContactKeys freshKeys{freshA.list(), fresh.b.data(), (unsigned int)nFresh};
        const ContactKeys oldKeys{oldA.list(), old.b.data(), (unsigned int)nOld};
        std::vector<unsigned long long> missing(nOld + 1, 0), before(nOld + 1, 0);
        unsigned int any = 0;
        runThreads(nOld, [&] { deme_persistent_missing(freshKeys, oldKeys, oldPersistent.data(), nullptr, &any); });
        ASSERT_EQ(any != 0, std::count(oldPersistent.begin(), oldPersistent.end(), 1) > 0);
        if (any)
            runThreads(nOld,
                       [&] { deme_persistent_missing(freshKeys, oldKeys, oldPersistent.data(), missing.data(), &any); });
        for (size_t j = 1; j <= nOld; j++) before[j] = before[j - 1] + missing[j - 1];
        const size_t total = nFresh + before[nOld];
        std::vector<bodyID_t> A(total), B(total);
        runThreads(nFresh + nOld, [&] {
            deme_persistent_merge(freshKeys, oldKeys, missing.data(), before.data(), A.data(), B.data());
        });
        ASSERT_EQ(A, c.geomA);
        ASSERT_EQ(B, c.geomB);
        std::vector<float> wildcards(total, -9.f);
        std::vector<uint8_t> meshState(total, 9), persistent(total, 9);
        StateView view{};
        view.spheres.owner = s.spheres.owner.data();
        view.owners.family = s.owners.family.data();
        view.numSpheres = spheres;
        const ContactInitRule rule{0, 1, 0, 7.f};
        const OldContactHistory history{
            oldKeys, oldWildcards.data(), oldMeshState.data(), any ? oldPersistent.data() : nullptr, 1, &rule, 1};
        const HostCompactPairAs mergedA = compactPairAsOnHost(A.data(), total);
        const ContactKeys mergedKeys{mergedA.list(), B.data(), (unsigned int)total};
        runThreads(total, [&] {
            deme_map_history(view, mergedKeys, history, wildcards.data(), meshState.data(), persistent.data());
        });
        EXPECT_EQ(persistent, c.persistent);
        EXPECT_EQ(meshState, c.meshState);
        densifyHistory(s);  // the CPU may keep it pooled (backend/cpu/HistoryForm.h)
        EXPECT_EQ(wildcards, c.wildcards);
        if (!any) {
            // A new set without flags (no old pair persistent, a model that sets none): the same
            // history and mesh states, and no flag written.
            std::vector<float> unflaggedWildcards(total, -9.f);
            std::vector<uint8_t> unflaggedMeshState(total, 9);
            runThreads(total, [&] {
                deme_map_history(view, mergedKeys, history, unflaggedWildcards.data(), unflaggedMeshState.data(),
                                 nullptr);
            });
            EXPECT_EQ(unflaggedWildcards, wildcards);
            EXPECT_EQ(unflaggedMeshState, meshState);
        }

        // The GPU's pooled form (state/HistoryPool.h), from the old set kept dense and kept pooled
        // (its nonzero histories in slots, in reverse order): slots only for the pairs whose history
        // is not zero, and read back per pair the dense mapping's wildcards; the same flags.
        std::vector<uint32_t> oldSlot(nOld, NO_HISTORY_SLOT);
        std::vector<float> oldPool;
        for (size_t j = nOld; j-- > 0;)
            if (oldWildcards[j] != 0.f) {
                oldSlot[j] = (uint32_t)oldPool.size();
                oldPool.push_back(oldWildcards[j]);
            }
        // The old set pooled as late pairs (a trimmed set's form: mesh states per pair), and ranked
        // (an installed set's: mesh states per slot; every old pair has a history, so every one is
        // ranked and can keep its mesh state there).
        deme_test::HostHistoryPool oldLate = deme_test::HostHistoryPool::allLate(oldSlot, 1);
        deme_test::HostHistoryPool oldRanked(nOld, std::vector<bool>(nOld, true), 1);
        ASSERT_EQ(std::count(oldWildcards.begin(), oldWildcards.end(), 0.f), 0);
        std::copy(oldWildcards.begin(), oldWildcards.end(), oldRanked.pool.begin());
        for (const int oldForm : {0, 1, 2}) {
            SCOPED_TRACE(oldForm == 0 ? "old set dense" : oldForm == 1 ? "old set pooled, late" : "old set ranked");
            OldContactHistory from = history;
            if (oldForm == 1) {
                from.wildcards = oldPool.data();
                from.slots = oldLate.view().slots();
            } else if (oldForm == 2) {
                from.wildcards = oldRanked.pool.data();
                from.slots = oldRanked.view().slots();
                from.meshStateBySlot = true;  // slot j is pair j's: the per-pair states serve as per-slot ones
            }
            Ranked r(total);
            runThreads(total, [&] { deme_mark_history_slots(view, mergedKeys, from, r.words.data()); });
            r.rank();
            const uint32_t withSlot = r.count();
            std::vector<float> pool(withSlot, -9.f), expanded(total);
            std::vector<uint8_t> slotMesh(withSlot, 9), pPersistent(total, 9);
            runThreads(total, [&] {
                deme_map_history_pooled(view, mergedKeys, from, r.ranked(), r.rankBase.data(), pool.data(),
                                        slotMesh.data(), pPersistent.data());
            });
            const std::vector<uint32_t> slots = r.slots();
            expandPooledHistory(slots.data(), total, pool.data(), 1, expanded.data());
            EXPECT_EQ(expanded, wildcards);
            EXPECT_EQ(r.meshStates(slotMesh), c.meshState);
            EXPECT_EQ(pPersistent, c.persistent);
            EXPECT_EQ((size_t)withSlot, total - (size_t)std::count(wildcards.begin(), wildcards.end(), 0.f));
            for (size_t i = 0; i < total; i++)
                EXPECT_EQ(slots[i] == NO_HISTORY_SLOT, wildcards[i] == 0.f) << "pair " << i;

            // From the old set's side (DeviceHistoryMapping: no contact-init rule, no old persistent
            // pair), against the dense mapping without the rule.
            if (any) continue;
            OldContactHistory plain = from;
            plain.rules = nullptr;
            plain.numRules = 0;
            std::vector<float> plainWildcards(total, -9.f);
            std::vector<uint8_t> plainMesh(total, 9), plainPersistent(total, 9);
            runThreads(total, [&] {
                deme_map_history(view, mergedKeys, plain, plainWildcards.data(), plainMesh.data(),
                                 plainPersistent.data());
            });
            Ranked m(total);
            runThreads(total, [&] { deme_mark_mesh_pairs(view, mergedKeys, m.words.data()); });
            runThreads(nOld, [&] { deme_mark_carried_pairs(mergedKeys, plain, m.words.data()); });
            m.rank();
            const uint32_t count = m.count();
            std::vector<float> markedPool(count, -9.f), markedExpanded(total);
            std::vector<uint8_t> markedMesh(count, 9), markedPersistent(total, 9);
            runThreads(total, [&] {
                deme_map_marked_history(view, mergedKeys, plain, m.ranked(), m.rankBase.data(), markedPool.data(),
                                        markedMesh.data(), markedPersistent.data());
            });
            const std::vector<uint32_t> marked = m.slots();
            expandPooledHistory(marked.data(), total, markedPool.data(), 1, markedExpanded.data());
            EXPECT_EQ(markedExpanded, plainWildcards);
            EXPECT_EQ(m.meshStates(markedMesh), plainMesh);
            EXPECT_EQ(markedPersistent, plainPersistent);
            EXPECT_EQ((size_t)count, total - (size_t)std::count(plainWildcards.begin(), plainWildcards.end(), 0.f));
            fromOldSide++;
        }
        newPairs +=
            std::count(wildcards.begin(), wildcards.end(), 7.f) + std::count(wildcards.begin(), wildcards.end(), 0.f);
    }
    EXPECT_GT(newPairs, 1000u);
    EXPECT_GT(fromOldSide, 80u);
}

// Before a synchronous detection the GPU's set in use keeps the pairs the CPU's keeps
// (backend/cpu/CarriedPairs.h): deme_mark_pairs_handed_on, the marks' exclusive sum and
// deme_keep_pairs_handed_on against keepOnlyCarriedPairs, with the set's history dense and
// pooled (each kept pair's slot then reads back the CPU's kept history).
TEST(CudaHistoryMapping, PairsHandedOnAreThoseTheCpuKeeps) {
    std::mt19937 rng(5);
    const unsigned int spheres = 60, W = 2;
    size_t trimmedRounds = 0;
    for (int round = 0; round < 100; round++) {
        SCOPED_TRACE(round);
        const deme_test::ScopedEnvironmentVariable form("DEME_CONTACT_HISTORY", "dense");
        const Pairs p = randomPairs(rng, spheres, std::uniform_int_distribution<size_t>(1, 300)(rng));
        const size_t n = p.a.size();
        SimState s;
        s.numWildcards = W;
        ContactArrays& c = s.contacts;
        c.geomA = p.a;
        c.geomB = p.b;
        c.wildcards.assign(n * W, 0.f);
        c.meshState.assign(n, 0);
        c.persistent.assign(n, 0);
        // About a fifth with a history (one of its two floats, or a -0), a few with a mesh state or
        // the flag; every pair in some rounds (then nothing is trimmed).
        const bool all = round % 10 == 0;
        for (size_t i = 0; i < n; i++) {
            const unsigned int r = rng() % 20;
            if (all || r < 3) c.wildcards[i * W + rng() % W] = r == 2 ? -0.f : (float)(rng() % 100) + 0.25f;
            if (r == 3) c.meshState[i] = (uint8_t)(1 + rng() % 3);
            if (r == 4) c.persistent[i] = 1;
        }
        const std::vector<bodyID_t> a = c.geomA, b = c.geomB;
        const std::vector<float> wildcards = c.wildcards;
        const std::vector<uint8_t> meshState = c.meshState, persistent = c.persistent;
        const bool cpuTrimmed = keepOnlyCarriedPairs(s);

        // Dense, then pooled (the nonzero histories in slots, in reverse order, as late pairs).
        std::vector<uint32_t> slot(n, NO_HISTORY_SLOT);
        std::vector<float> pool;
        for (size_t j = n; j-- > 0;)
            if (!isPositiveZero(wildcards[j * W]) || !isPositiveZero(wildcards[j * W + 1])) {
                slot[j] = (uint32_t)(pool.size() / W);
                pool.insert(pool.end(), wildcards.begin() + j * W, wildcards.begin() + (j + 1) * W);
            }
        deme_test::HostHistoryPool gpuPool = deme_test::HostHistoryPool::allLate(slot, W);
        for (const bool pooled : {false, true}) {
            SCOPED_TRACE(pooled ? "pooled" : "dense");
            OldContactHistory set{ContactKeys{wholePairAs(a.data()), b.data(), (unsigned int)n},
                                  pooled ? pool.data() : wildcards.data(),
                                  meshState.data(),
                                  persistent.data(),
                                  W,
                                  nullptr,
                                  0u};
            if (pooled) set.slots = gpuPool.view().slots();
            // The marks (a bit a pair), each word's count and their exclusive sum.
            const size_t words = (n + 63) / 64;
            std::vector<unsigned long long> marks(words, 0ull);
            std::vector<uint32_t> rankBase(words + 1, 99u);
            runThreadsReversed(n, [&] { deme_mark_pairs_handed_on(set, marks.data()); });
            runThreads(words + 1, [&] { deme_count_marks(marks.data(), (unsigned int)words, rankBase.data()); });
            uint32_t sum = 0;
            for (uint32_t& v : rankBase) {
                const uint32_t count = v;
                ASSERT_LE(count, 64u);
                v = sum;
                sum += count;
            }
            const size_t kept = rankBase[words];
            ASSERT_EQ(keepingOnlyPairsHandedOnPays(n, kept), cpuTrimmed);
            if (!cpuTrimmed) continue;
            ASSERT_EQ(kept, c.size());
            std::vector<bodyID_t> ka(kept), kb(kept);
            std::vector<uint8_t> km(kept), kp(kept);
            std::vector<float> kw(pooled ? 0 : kept * W);
            // A pooled set's kept pairs become the trimmed set's late pairs (DeviceHistoryMapping).
            const size_t keptWords = (kept + 63) / 64;
            std::vector<unsigned long long> keptLate(pooled ? keptWords : 0, 0ull),
                keptTable(pooled ? lateTableEntriesFor(kept, 0) : 0, 0ull);
            runThreads(n, [&] {
                deme_keep_pairs_handed_on(set, marks.data(), rankBase.data(), ka.data(), kb.data(), km.data(),
                                          kp.data(), kw.data(), keptLate.data(), keptTable.data(),
                                          pooled ? (uint32_t)(keptTable.size() - 1) : 0u);
            });
            std::vector<uint32_t> ks(kept, NO_HISTORY_SLOT);
            if (pooled) {
                const std::vector<uint64_t> noneRanked(keptWords, 0ull);
                const std::vector<uint32_t> noRanks(keptWords + 1, 0u);
                RankedSlotsView v;
                v.ranked = noneRanked.data();
                v.rankBase = noRanks.data();
                v.late = (const uint64_t*)keptLate.data();
                v.lateTable = keptTable.data();
                v.lateMask = (uint32_t)(keptTable.size() - 1);
                for (size_t k = 0; k < kept; k++) ks[k] = slotOf(v, k);
            }
            EXPECT_EQ(ka, c.geomA);
            EXPECT_EQ(kb, c.geomB);
            EXPECT_EQ(km, c.meshState);
            EXPECT_EQ(kp, c.persistent);
            if (pooled)
                for (size_t k = 0; k < kept; k++)
                    for (unsigned int w = 0; w < W; w++) {
                        const float v = ks[k] == NO_HISTORY_SLOT ? 0.f : pool[(size_t)ks[k] * W + w];
                        EXPECT_EQ(std::signbit(v), std::signbit(c.wildcards[k * W + w])) << k;
                        EXPECT_EQ(v, c.wildcards[k * W + w]) << k;
                    }
            else
                for (size_t k = 0; k < kept * W; k++) {
                    EXPECT_EQ(std::signbit(kw[k]), std::signbit(c.wildcards[k])) << k;
                    EXPECT_EQ(kw[k], c.wildcards[k]) << k;
                }
        }
        trimmedRounds += cpuTrimmed;
    }
    EXPECT_GT(trimmedRounds, 50u);
}
