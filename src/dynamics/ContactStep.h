// The per-contact step of the force pass, written once for the CPU's loop
// (backend/cpu/ForcePassLoop.h) and the GPU's kernel (backend/cuda/kernels/ForcePassKernel.cuh):
// for one pair of the active-contact set, decide whether the model sees it, gather the model's
// inputs (paper Table 3), run the model, and return the force on A and the torques about both
// owners. The two loops differ only in how the loads reach the owners (the CPU stores them per
// contact and each owner sums its contacts in a fixed order; the GPU adds them with atomics).
//
// The rules:
//   - sphere-triangle contacts the mesh rule did not count this step (meshState bit 0) get no call;
//   - a model that does not see apart pairs (the built-in ones) gets no call for pairs that do not
//     overlap: zero force, and the pair's history ends (wildcards cleared: a later touch starts
//     afresh), as in the paper's default model. Most such pairs are sphere pairs, told apart from
//     their centres alone before any gather; that bound is looser than the exact overlap test by
//     1e-9 (relative), far more than rounding, so it never drops a pair the exact test keeps;
//   - a model that sees apart pairs (custom models, docs/force-models.md) is called for every pair
//     whose geometry counts, touching or not, and its force applies either way;
//   - a model that writes `persistent` gets the contact's flag, and its value is stored back.
//
// A model is a functor type with
//   static constexpr unsigned int kNumContactWildcards;  // floats of history per contact
//   static constexpr bool kSeesApartPairs;    // called for pairs with overlapDepth <= 0 too
//   static constexpr bool kWritesPersistent;  // may change the contact's `persistent` flag
//   static constexpr bool kWritesCouple;      // may set `couple_torque` (else it is not added)
//   void operator()(const ContactInputs& in, float* contactWildcards, float3& force,
//                   float3& torque_only_force, float3& couple_torque, bool& persistent) const;
#pragma once

#include "dynamics/ContactInputsGather.h"
#include "state/SphereLayout.h"

namespace deme {

// What one contact exerts: the force on A (B gets -force) and the torques about each owner's
// centre (global), and the two owners.
struct ContactLoad {
    float3 force, torqueA, torqueB;
    bodyID_t ownerA, ownerB;
};

// Contact i's step. Returns whether the pair touches (overlap > 0: a real contact); `applied` says
// whether `load` holds what it exerts (the model was called). `SphereSphere`: the caller knows the
// pair is a sphere pair, so the other geometry branches drop out of that path.
template <class Model, bool SphereSphere, class S>
DEME_HD_INLINE bool contactStep(S& s, const Model& model, size_t i, float time, float dt, bool& applied,
                                ContactLoad& load) {
    auto& c = s.contacts;
    // The wildcard count is a constant of the model, so history loops unroll.
    constexpr unsigned int W = Model::kNumContactWildcards;
    float* wc = W ? &c.wildcards[i * W] : nullptr;
    const uint8_t type = SphereSphere ? (uint8_t)SPHERE_SPHERE : c.type[i];
    bool gather = type != SPHERE_TRIANGLE || (c.meshState[i] & 1u);
    if (!Model::kSeesApartPairs && (SphereSphere || type == SPHERE_SPHERE)) {
        const double3 pA = sphereCentre(s, c.geomA[i]);
        const double3 d = pA - nearestImage(s.frame.periodic, pA, sphereCentre(s, c.geomB[i]));
        const double reach = (double)s.spheres.radius[c.geomA[i]] + (double)s.spheres.radius[c.geomB[i]];
        gather = dot(d, d) < reach * reach * (1.0 + 1e-9);
    }
    ContactInputs in;
    if (gather) gatherContactInputsOfType(s, i, type, time, dt, in);
    const bool touching = gather && in.overlapDepth > 0.0;
    applied = Model::kSeesApartPairs ? gather : touching;
    if (!applied) {
        // No call: no force, and the contact's history ends.
        for (unsigned int w = 0; w < W; w++) wc[w] = 0.f;
        return false;
    }
    float3 force = make_float3(0.f), torque_only_force = make_float3(0.f), couple_torque = make_float3(0.f);
    bool persistent = Model::kWritesPersistent && c.persistent[i] != 0;
    model(in, wc, force, torque_only_force, couple_torque, persistent);
    if (Model::kWritesPersistent) c.persistent[i] = persistent ? 1 : 0;
    const float3 total = force + torque_only_force;
    load.force = force;
    // The couple acts on A as given and on B reversed: a pure couple (a bent bond, a relative
    // rolling resistance) turns the two owners in opposite senses, which no force pair at the
    // contact point can do.
    load.torqueA = cross(in.armA, total);
    load.torqueB = cross(in.armB, -total);
    if (Model::kWritesCouple) {  // compiled out for the built-in models, which leave it at zero
        load.torqueA += couple_torque;
        load.torqueB -= couple_torque;
    }
    load.ownerA = in.AOwner;
    load.ownerB = in.BOwner;
    return touching;
}

}  // namespace deme
