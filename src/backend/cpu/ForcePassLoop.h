// The CPU's force pass as a template over the contact force model: every pair of the active-contact
// set takes the per-contact step of dynamics/ContactStep.h (where the rules are), and its force on A
// and torques about both owners are stored per contact for the reduction, which sums each owner's
// contacts in a fixed order (bit-identical for any thread count). The built-in models
// (ForcePass.cpp) and the code generated for a user's model at run time (forcemodel/CodeGen.cpp)
// instantiate this same loop, so a model written as a snippet computes bit for bit what the same
// model built into the library does (test ForceModelBitIdentity).
#pragma once

#include "parallel/Parallel.h"
#include "dynamics/ContactStep.h"
#include "backend/cpu/ForcePassResult.h"
#include "state/SimState.h"

namespace deme {

// One contact of the set (dynamics/ContactStep.h), its loads stored per contact for the reduction.
// Instantiated separately for sphere-sphere contacts (most of any granular scene) so that the
// compiler drops the other geometry branches from that path.
template <class Model, bool SphereSphere>
DEME_HD_INLINE bool forcePassContact(SimState& s, const Model& model, size_t i, float time, float dt) {
    ContactArrays& c = s.contacts;
    bool applied;
    ContactLoad load;
    const bool touching = contactStep<Model, SphereSphere>(s, model, i, time, dt, applied, load);
    c.force[i] = applied ? load.force : make_float3(0.f);
    c.torqueA[i] = applied ? load.torqueA : make_float3(0.f);
    c.torqueB[i] = applied ? load.torqueB : make_float3(0.f);
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
