#include "backend/cpu/ForcePass.h"

#include <deme/Error.h>

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
    // A's side: the set is sorted by A, and A is always a sphere, whose owners ascend with their
    // ids (state/SimState.h), so each owner's contacts as A are one run.
    c.ownerAStart.assign(nOwners + 1, 0);
    bodyID_t prev = 0;
    for (size_t i = 0; i < n; i++) {
        const bodyID_t o = s.spheres.owner[c.geomA[i]];
        if (o < prev) throwError("contact detection", "internal: the contact set is not sorted by A's owner");
        if (o >= nOwners) throwError("contact detection", "internal: a contact's owner is not in the state");
        prev = o;
        c.ownerAStart[o + 1]++;
    }
    for (size_t o = 0; o < nOwners; o++) c.ownerAStart[o + 1] += c.ownerAStart[o];
    // B's side: per owner, its contacts as B in contact order (a fixed order for its sums). B's
    // owner is looked up twice rather than kept: a list of them would be 4 B per pair more at the
    // moment a new set's memory peaks.
    c.ownerBStart.assign(nOwners + 1, 0);
    for (size_t i = 0; i < n; i++) {
        const bodyID_t o = contactOwnerB(s, i);
        if (o >= nOwners) throwError("contact detection", "internal: a contact's owner is not in the state");
        c.ownerBStart[o + 1]++;
    }
    for (size_t o = 0; o < nOwners; o++) c.ownerBStart[o + 1] += c.ownerBStart[o];
    c.ownerBEntries.resize(n);
    std::vector<uint32_t> fill(c.ownerBStart.begin(), c.ownerBStart.end() - 1);
    for (size_t i = 0; i < n; i++) c.ownerBEntries[fill[contactOwnerB(s, i)]++] = (uint32_t)i;
}

}  // namespace deme
