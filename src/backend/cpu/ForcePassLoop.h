// The CPU's force pass as a template over the contact force model: every pair of the active-contact
// set takes the per-contact step of dynamics/ContactStep.h (where the rules are), and its force on A
// and the torque about B's owner are stored per contact for the reduction, A's owner takes its share
// in the pass itself; both sum each owner's contacts in a fixed order (bit-identical for any thread
// count). The built-in models
// (ForcePass.cpp) and the code generated for a user's model at run time (forcemodel/CodeGen.cpp)
// instantiate this same loop, so a model written as a snippet computes bit for bit what the same
// model built into the library does (test ForceModelBitIdentity).
#pragma once

#include <algorithm>

#include "parallel/Parallel.h"
#include "dynamics/ContactStep.h"
#include "backend/cpu/ForcePassResult.h"
#include "state/SimState.h"

namespace deme {

// One contact of the set (dynamics/ContactStep.h): the force on A and the torque about B's owner are
// stored per contact (B's owner sums them in the reduction); the torque about A's owner is handed
// back for the pass to add to A's owner at once. Instantiated separately for sphere-sphere contacts
// (most of any granular scene) so that the compiler drops the other geometry branches from that path.
template <class Model, bool SphereSphere>
DEME_HD_INLINE bool forcePassContact(SimState& s, const Model& model, size_t i, float time, float dt,
                                     float3& torqueA) {
    ContactArrays& c = s.contacts;
    bool applied;
    ContactLoad load;
    const bool touching = contactStep<Model, SphereSphere>(s, model, i, time, dt, applied, load);
    c.force[i] = applied ? load.force : make_float3(0.f);
    c.torqueB[i] = applied ? load.torqueB : make_float3(0.f);
    torqueA = applied ? load.torqueA : make_float3(0.f);
    return touching;
}

// Contacts per step of a thread's sweep: short enough for its A torques to stay in the cache.
constexpr size_t FORCE_PASS_CHUNK = 256;

// Thread t's share of the contacts: about n / T of them, cut only where A's owner changes, so
// that every owner's contacts as A fall to one thread.
inline void ownerAlignedRange(const SimState& s, int t, int T, size_t& begin, size_t& end) {
    const ContactArrays& c = s.contacts;
    const size_t n = c.size();
    auto ownerRunStart = [&](size_t k) -> size_t {
        if (k == 0 || k >= n) return k < n ? k : n;
        return c.ownerAStart[s.spheres.owner[c.geomA[k]]];
    };
    threadRange(n, t, T, begin, end);
    begin = ownerRunStart(begin);
    end = ownerRunStart(end);
}

template <class Model>
ForcePassResult runForcePass(SimState& s, const Model& model, double time, double dt) {
    const ContactArrays& c = s.contacts;
    OwnerArrays& ow = s.owners;
    const size_t n = c.size();
    const float t = (float)time, h = (float)dt;
    const int T = n > PARALLEL_MIN_ITEMS ? cpuThreadCount() : 1;
    size_t real = 0, realSS = 0;
#pragma omp parallel num_threads(T) if (T > 1) reduction(+ : real, realSS)
    {
        size_t begin, end;
        ownerAlignedRange(s, cpuThreadIndex(), T, begin, end);
        float3 torqueA[FORCE_PASS_CHUNK];
        bodyID_t owner = 0;
        float3 F = make_float3(0.f), tau = make_float3(0.f);
        for (size_t b = begin; b < end; b += FORCE_PASS_CHUNK) {
            const size_t m = std::min(FORCE_PASS_CHUNK, end - b);
            // Sphere pairs first, as one vectorisable sweep (masked lanes for other types) ...
#pragma omp simd reduction(+ : realSS)
            for (size_t j = 0; j < m; j++)
                if (c.type[b + j] == SPHERE_SPHERE)
                    realSS += forcePassContact<Model, true>(s, model, b + j, t, h, torqueA[j]);
            // ... then the rest ...
            for (size_t j = 0; j < m; j++)
                if (c.type[b + j] != SPHERE_SPHERE)
                    real += forcePassContact<Model, false>(s, model, b + j, t, h, torqueA[j]);
            // ... and A's loads onto A's owner in contact order: the sums do not depend on the
            // thread count. The reduction adds what the owner takes as B.
            for (size_t j = 0; j < m; j++) {
                const bodyID_t o = s.spheres.owner[c.geomA[b + j]];
                if (o != owner || b + j == begin) {
                    if (b + j != begin) {
                        ow.contactForce[owner] = F;
                        ow.contactTorque[owner] = tau;
                    }
                    owner = o;
                    F = tau = make_float3(0.f);
                }
                F += c.force[b + j];
                tau += torqueA[j];
            }
        }
        if (end > begin) {
            ow.contactForce[owner] = F;
            ow.contactTorque[owner] = tau;
        }
    }
    return ForcePassResult{real + realSS, realSS};
}

}  // namespace deme
