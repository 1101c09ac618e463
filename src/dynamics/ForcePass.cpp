#include "dynamics/ForcePass.h"

#include "backend/cpu/Parallel.h"
#include "dynamics/ContactInputsGather.h"
#include "physics/DefaultForceModel.h"

namespace deme {

namespace {

// One contact of the set: its inputs, the model, and the stored force and torques. Instantiated
// separately for sphere-sphere contacts (most of any granular scene) so that the compiler drops the
// other geometry branches from that path.
template <bool SphereSphere>
DEME_HD_INLINE bool processContact(SimState& s, size_t i, float time, float dt, const DefaultModelMaterials& mat) {
    ContactArrays& c = s.contacts;
    // The built-in model's wildcard count is a constant, so its history loops unroll.
    constexpr unsigned int W = DEFAULT_MODEL_NUM_WILDCARDS;
    float* wc = c.wildcards.data() + i * W;
    bool touching;
    ContactInputs in;
    if (SphereSphere) {
        // Most pairs in the set that are apart are sphere pairs: tell them cheaply.
        const double3 d = s.cache.spherePos[c.geomA[i]] - s.cache.spherePos[c.geomB[i]];
        const double reach = (double)s.spheres.radius[c.geomA[i]] + (double)s.spheres.radius[c.geomB[i]];
        touching = dot(d, d) < reach * reach;
        if (touching) gatherContactInputsOfType(s, i, SPHERE_SPHERE, time, dt, in);
    } else {
        gatherContactInputsOfType(s, i, c.type[i], time, dt, in);
        const bool counts = c.type[i] != SPHERE_TRIANGLE || (c.meshState[i] & 1u);
        touching = in.overlapDepth > 0.0 && counts;
    }
    if (!touching) {
        // Apart: no force, and the contact's history ends (a later touch starts fresh).
        for (unsigned int w = 0; w < W; w++) wc[w] = 0.f;
        c.force[i] = c.torqueA[i] = c.torqueB[i] = make_float3(0.f);
        return false;
    }
    float3 force = make_float3(0.f), torque_only_force = make_float3(0.f);
    defaultForceModel(in, mat, wc, force, torque_only_force);
    const float3 total = force + torque_only_force;
    c.force[i] = force;
    c.torqueA[i] = cross(in.armA, total);
    c.torqueB[i] = cross(in.armB, -total);
    return true;
}

}  // namespace

ForcePassResult computeContactForces(SimState& s, double time, double dt) {
    ContactArrays& c = s.contacts;
    const size_t n = c.size();
    const MaterialTables& mt = s.materials;
    const unsigned int nm = mt.count;
    const DefaultModelMaterials mat{PairTable{mt.mu.data(), nm}, PairTable{mt.Crr.data(), nm},
                                    PairTable{mt.E_eff.data(), nm}, PairTable{mt.G_eff.data(), nm},
                                    PairTable{mt.beta_CoR.data(), nm}};
    size_t real = 0, realSS = 0;
#pragma omp parallel if (n > PARALLEL_MIN_ITEMS)
    {
        // Sphere pairs first, as one vectorisable sweep (masked lanes for other types) ...
#pragma omp for simd schedule(static) reduction(+ : realSS) nowait
        for (size_t i = 0; i < n; i++)
            if (c.type[i] == SPHERE_SPHERE) realSS += processContact<true>(s, i, (float)time, (float)dt, mat);
        // ... then the rest, with the same static split so each thread revisits its own range.
#pragma omp for schedule(static) reduction(+ : real)
        for (size_t i = 0; i < n; i++)
            if (c.type[i] != SPHERE_SPHERE) real += processContact<false>(s, i, (float)time, (float)dt, mat);
    }
    real += realSS;
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
