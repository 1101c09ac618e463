#include "backend/cpu/ForcePass.h"

#include "parallel/Parallel.h"
#include "backend/cpu/ForcePassLoop.h"
#include "physics/BuiltInForceModels.h"

namespace deme {

namespace {

PairTable pairTable(const std::vector<float>& table, unsigned int n) { return PairTable{table.data(), n}; }

}  // namespace

ForcePassResult frictionalHertzForcePass(SimState& s, double time, double dt) {
    const MaterialTables& mt = s.materials;
    const unsigned int n = mt.count;
    const FrictionalHertzModel model{pairTable(mt.mu, n), pairTable(mt.Crr, n), pairTable(mt.E_eff, n),
                                     pairTable(mt.G_eff, n), pairTable(mt.beta_CoR, n)};
    return runForcePass(s, model, time, dt);
}

ForcePassResult frictionlessHertzForcePass(SimState& s, double time, double dt) {
    const MaterialTables& mt = s.materials;
    const FrictionlessHertzModel model{pairTable(mt.E_eff, mt.count), pairTable(mt.beta_CoR, mt.count)};
    return runForcePass(s, model, time, dt);
}

void buildOwnerContactIndex(SimState& s) {
    ContactArrays& c = s.contacts;
    const size_t n = c.size();
    const size_t nOwners = s.owners.size();
    std::vector<bodyID_t> ownerB(n);
#pragma omp parallel for schedule(static) if (n > PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) ownerB[i] = contactOwnerB(s, i);
    c.ownerStart.assign(nOwners + 1, 0);
    for (size_t i = 0; i < n; i++) {
        c.ownerStart[s.spheres.owner[c.geomA[i]] + 1]++;
        c.ownerStart[ownerB[i] + 1]++;
    }
    for (size_t o = 0; o < nOwners; o++) c.ownerStart[o + 1] += c.ownerStart[o];
    c.ownerEntries.resize(c.ownerStart[nOwners]);
    std::vector<uint32_t> fill(c.ownerStart.begin(), c.ownerStart.end() - 1);
    // Serial fill in contact order: each owner sums its contacts in a fixed order, so results do
    // not depend on the thread count.
    for (size_t i = 0; i < n; i++) {
        c.ownerEntries[fill[s.spheres.owner[c.geomA[i]]]++] = (uint32_t)(i << 1);
        c.ownerEntries[fill[ownerB[i]]++] = (uint32_t)((i << 1) | 1u);
    }
}

}  // namespace deme
