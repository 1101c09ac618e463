// The force pass as a template over the contact force model: for every pair of the active-contact
// set, gather the model's inputs (paper Table 3), run the model, store the force on A and the torques
// about both owners. The built-in models (ForcePass.cpp) and the code generated for a user's model at
// run time (forcemodel/CodeGen.cpp) instantiate this same loop, so a model written as a snippet
// computes bit for bit what the same model built into the library does (test ForceModelBitIdentity).
//
// A model is a functor type with
//   static constexpr unsigned int kNumContactWildcards;  // floats of history per contact
//   static constexpr bool kSeesApartPairs;    // called for pairs with overlapDepth <= 0 too
//   static constexpr bool kWritesPersistent;  // may change the contact's `persistent` flag
//   void operator()(const ContactInputs& in, float* contactWildcards, float3& force,
//                   float3& torque_only_force, bool& persistent) const;
// A model that does not see apart pairs gets no call for them: they get zero force and their
// wildcards are cleared (a later touch starts afresh), as in the paper's default model, and sphere
// pairs that are clearly apart skip the gather. Custom models see every pair (docs/force-models.md).
#pragma once

#include "parallel/Parallel.h"
#include "dynamics/ContactInputsGather.h"
#include "backend/cpu/ForcePassResult.h"
#include "state/SimState.h"

namespace deme {

// One contact of the set; returns whether the pair overlaps (and, for a mesh contact, counts).
// Instantiated separately for sphere-sphere contacts (most of any granular scene) so that the
// compiler drops the other geometry branches from that path.
template <class Model, bool SphereSphere>
DEME_HD_INLINE bool forcePassContact(SimState& s, const Model& model, size_t i, float time, float dt) {
    ContactArrays& c = s.contacts;
    // The wildcard count is a constant of the model, so history loops unroll.
    constexpr unsigned int W = Model::kNumContactWildcards;
    float* wc = c.wildcards.data() + i * W;
    const uint8_t type = SphereSphere ? (uint8_t)SPHERE_SPHERE : c.type[i];
    // Mesh contacts that do not count this step (backend/cpu/MeshContacts.h) are never passed on.
    bool gather = SphereSphere || type != SPHERE_TRIANGLE || (c.meshState[i] & 1u);
    if (SphereSphere && !Model::kSeesApartPairs) {
        // Most pairs of the set that are apart are sphere pairs: tell them without the full gather.
        // The bound is looser than the exact test below by 1e-9 (relative), far more than rounding,
        // so that it never drops a pair that test keeps: the outcome is the exact test's alone.
        const double3 d = s.cache.spherePos[c.geomA[i]] - s.cache.spherePos[c.geomB[i]];
        const double reach = (double)s.spheres.radius[c.geomA[i]] + (double)s.spheres.radius[c.geomB[i]];
        gather = dot(d, d) < reach * reach * (1.0 + 1e-9);
    }
    ContactInputs in;
    if (gather) gatherContactInputsOfType(s, i, type, time, dt, in);
    const bool touching = gather && in.overlapDepth > 0.0;
    if (!(Model::kSeesApartPairs ? gather : touching)) {
        // No call: no force, and the contact's history ends.
        for (unsigned int w = 0; w < W; w++) wc[w] = 0.f;
        c.force[i] = c.torqueA[i] = c.torqueB[i] = make_float3(0.f);
        return false;
    }
    float3 force = make_float3(0.f), torque_only_force = make_float3(0.f);
    bool persistent = Model::kWritesPersistent && c.persistent[i] != 0;
    model(in, wc, force, torque_only_force, persistent);
    if (Model::kWritesPersistent) c.persistent[i] = persistent ? 1 : 0;
    const float3 total = force + torque_only_force;
    c.force[i] = force;
    c.torqueA[i] = cross(in.armA, total);
    c.torqueB[i] = cross(in.armB, -total);
    return touching;
}

template <class Model>
ForcePassResult runForcePass(SimState& s, const Model& model, double time, double dt) {
    const ContactArrays& c = s.contacts;
    const size_t n = c.size();
    const float t = (float)time, h = (float)dt;
    size_t real = 0, realSS = 0;
#pragma omp parallel if (n > PARALLEL_MIN_ITEMS)
    {
        // Sphere pairs first, as one vectorisable sweep (masked lanes for other types) ...
#pragma omp for simd schedule(static) reduction(+ : realSS) nowait
        for (size_t i = 0; i < n; i++)
            if (c.type[i] == SPHERE_SPHERE) realSS += forcePassContact<Model, true>(s, model, i, t, h);
                // ... then the rest, with the same static split so each thread revisits its own range.
#pragma omp for schedule(static) reduction(+ : real)
        for (size_t i = 0; i < n; i++)
            if (c.type[i] != SPHERE_SPHERE) real += forcePassContact<Model, false>(s, model, i, t, h);
    }
    return ForcePassResult{real + realSS, realSS};
}

}  // namespace deme
