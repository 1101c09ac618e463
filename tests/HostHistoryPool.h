// The GPU's pooled history (state/HistoryPool.h) held on the host, for tests that run its per-pair
// rules without a GPU: ranked bits and their words' first ranks, late bits and the late table, the
// pool (W floats a slot) and the per-slot forces, with what CudaDynamics does to them (the table
// sized by lateTableEntriesFor and rehashed as the pool grows).
#pragma once

#include <vector>

#include "runtime/HistoryPoolPolicy.h"
#include "state/HistoryPool.h"

namespace deme_test {

struct HostHistoryPool {
    std::vector<uint64_t> ranked, late;
    std::vector<uint32_t> rankBase;
    std::vector<unsigned long long> table;
    std::vector<float> pool;
    std::vector<deme::float3> force;  // per slot
    deme::HistoryPoolControl control{};
    uint32_t capacity = 0, rankedSlots = 0;
    unsigned int W = 1;

    // n pairs, those with mark[i] ranked (their slots their ranks; a slot holds garbage until
    // written), the pool just large enough for them.
    HostHistoryPool(size_t n, const std::vector<bool>& mark, unsigned int w) : W(w) {
        const size_t words = (n + 63) / 64;
        ranked.assign(words, 0ull);
        late.assign(words, 0ull);
        rankBase.assign(words + 1, 0u);
        for (size_t i = 0; i < n; i++)
            if (mark[i]) ranked[i >> 6] |= 1ull << (i & 63);
        for (size_t w = 0; w < words; w++) rankBase[w + 1] = rankBase[w] + deme::popcount64(ranked[w]);
        rankedSlots = rankBase[words];
        control.used = rankedSlots;
        table.assign(deme::lateTableEntriesFor(0, 0), 0ull);
        grow(rankedSlots);
    }
    // Every pair with a slot given (NO_HISTORY_SLOT: none) a late pair with that slot.
    static HostHistoryPool allLate(const std::vector<uint32_t>& slot, unsigned int w) {
        HostHistoryPool p(slot.size(), std::vector<bool>(slot.size(), false), w);
        uint32_t most = 0;
        for (uint32_t k : slot)
            if (k != deme::NO_HISTORY_SLOT && k + 1 > most) most = k + 1;
        p.grow(most);
        for (size_t i = 0; i < slot.size(); i++)
            if (slot[i] != deme::NO_HISTORY_SLOT) p.view().giveLateSlot(i, slot[i]);
        return p;
    }
    void grow(uint32_t to) {
        if (to < capacity) return;
        capacity = to;
        pool.resize((size_t)to * W, -7.f);  // new slots hold garbage until written
        force.resize(to, deme::make_float3(-7.f));
        const size_t entries = deme::lateTableEntriesFor(capacity, rankedSlots);
        if (entries <= table.size()) return;
        std::vector<unsigned long long> old(entries, 0ull);
        old.swap(table);
        for (unsigned long long e : old)
            if (e)
                deme::insertLateSlot(table.data(), (uint32_t)(table.size() - 1), deme::lateEntryPair(e),
                                     deme::lateEntrySlot(e));
    }
    deme::HistoryPoolView view() {
        deme::HistoryPoolView v;
        v.ranked = ranked.data();
        v.rankBase = rankBase.data();
        v.late = (unsigned long long*)late.data();
        v.lateTable = table.data();
        v.lateMask = (uint32_t)(table.size() - 1);
        v.pool = pool.data();
        v.control = &control;
        v.capacity = capacity;
        return v;
    }
    // Each pair's slot, as the host reads a pooled set back.
    std::vector<uint32_t> slots(size_t n) {
        std::vector<uint32_t> s(n);
        const deme::HistoryPoolView v = view();
        for (size_t i = 0; i < n; i++) s[i] = v.slotOf(i);
        return s;
    }
};

}  // namespace deme_test
