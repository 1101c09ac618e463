#include "dynamics/ForcePass.h"

#include "backend/cpu/Parallel.h"
#include "dynamics/ContactInputsGather.h"
#include "physics/DefaultForceModel.h"

namespace deme {

ForcePassResult computeContactForces(SimState& s, double time, double dt) {
    ContactArrays& c = s.contacts;
    const size_t n = c.size();
    const unsigned int W = s.numWildcards;
    const MaterialTables& mt = s.materials;
    const DefaultModelMaterials mat{mt.E.data(), mt.nu.data(), PairTable{mt.CoR.data(), mt.count},
                                    PairTable{mt.mu.data(), mt.count}, PairTable{mt.Crr.data(), mt.count}};
    size_t real = 0, realSS = 0;
#pragma omp parallel for schedule(static) reduction(+ : real, realSS) if (n > PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) {
        float* wc = c.wildcards.data() + i * W;
        if (c.type[i] == SPHERE_SPHERE) {
            // Most pairs in the set that are apart are sphere pairs: tell them cheaply.
            const double3 d = s.cache.spherePos[c.geomA[i]] - s.cache.spherePos[c.geomB[i]];
            const double reach = (double)s.spheres.radius[c.geomA[i]] + (double)s.spheres.radius[c.geomB[i]];
            if (!(dot(d, d) < reach * reach)) {
                for (unsigned int w = 0; w < W; w++) wc[w] = 0.f;
                c.force[i] = c.torqueA[i] = c.torqueB[i] = make_float3(0.f);
                continue;
            }
        }
        ContactInputs in;
        gatherContactInputs(s, i, (float)time, (float)dt, in);
        const bool counts = c.type[i] != SPHERE_TRIANGLE || (c.meshState[i] & 1u);
        if (!(in.overlapDepth > 0.0) || !counts) {
            // Apart: no force, and the contact's history ends (a later touch starts fresh).
            for (unsigned int w = 0; w < W; w++) wc[w] = 0.f;
            c.force[i] = c.torqueA[i] = c.torqueB[i] = make_float3(0.f);
            continue;
        }
        real++;
        if (c.type[i] == SPHERE_SPHERE) realSS++;
        float3 force = make_float3(0.f), torque_only_force = make_float3(0.f);
        defaultForceModel(in, mat, wc, force, torque_only_force);
        const float3 total = force + torque_only_force;
        c.force[i] = force;
        c.torqueA[i] = cross(in.armA, total);
        c.torqueB[i] = cross(in.armB, -total);
    }
    return ForcePassResult{real, realSS};
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
