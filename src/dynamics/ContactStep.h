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
#include "dynamics/OwnerStepFlags.h"
#include "state/ContactTypeOf.h"
#include "state/HistorySlot.h"
#include "state/SphereLayout.h"

namespace deme {

// Sphere pairs told apart from their centres before the gather (the rule above). 0 gathers every pair
// and lets the exact overlap decide: the same pairs, the same bits, one dependent round of loads
// fewer for the pairs that touch. So the GPU's pass goes without the test (measured on one H100,
// 2026-12-06: SMALL-SYSTEMS 3-4 % more steps a second without it, BENCHMARKS.md) and the CPU's
// keeps it, a gather costing it far more than the test. DEME_CUDA_DEFINES="DEME_CENTRE_PRETEST=1"
// times the GPU's pass with it.
#ifndef DEME_CENTRE_PRETEST
#ifdef __CUDA_ARCH__
#define DEME_CENTRE_PRETEST 0
#else
#define DEME_CENTRE_PRETEST 1
#endif
#endif

// A large set's sphere pairs that are out of reach by their voxel codes alone are turned away
// before their centres are decoded (state/OwnerCentre.h, apartByVoxelCodes): on a GPU a partner's
// centre is four scattered loads from memory, its voxel code one. Only where the GPU's dynamics sets
// StateView::voxelPretest: spheres that are their owners, no periodic axis, and a set of at least
// VOXEL_PRETEST_MIN_PAIRS (state/StateView.h) pairs of which fewer than half touched in the step before it was
// installed. Measured on one H100 (2026-12-07, BENCHMARKS.md, MEMORY): the early mixer (45.8 M
// spheres, all its pairs apart) 1.91e9 -> 2.29e9 sphere-steps/s, its force pass 0.738 -> 0.481 s;
// SMALL-SYSTEMS' drum and impact (about 200,000 pairs, held in the GPU's L2, where a scattered load
// is cheap) 2-5 % slower with it, hence the set's size. The same pairs, the same bits: the test
// never turns away a pair the exact overlap finds touching. The CPU's vectorised sweep decodes both
// centres anyway and keeps its exact test alone (above).
#ifndef DEME_VOXEL_PRETEST
#ifdef __CUDA_ARCH__
#define DEME_VOXEL_PRETEST 1
#else
#define DEME_VOXEL_PRETEST 0
#endif
#endif

// Histories of at most this many floats are copied into registers for the model (contactStepWithHistory).
constexpr unsigned int MAX_COPIED_HISTORY = 8;

// A contact's W history floats between its slot and registers: as float4s on the GPU where W is a
// multiple of four and the slot is aligned (one 16-byte access instead of four strided ones).
template <unsigned int W>
DEME_HD_INLINE void loadHistory(const float* slot, float* regs) {
#ifdef __CUDA_ARCH__
    if (W % 4 == 0 && (reinterpret_cast<size_t>(slot) & 15u) == 0) {
        for (unsigned int w = 0; w < W; w += 4) {
            const float4 v = *reinterpret_cast<const float4*>(slot + w);
            regs[w] = v.x, regs[w + 1] = v.y, regs[w + 2] = v.z, regs[w + 3] = v.w;
        }
        return;
    }
#endif
    for (unsigned int w = 0; w < W; w++) regs[w] = slot[w];
}

template <unsigned int W>
DEME_HD_INLINE void storeHistory(const float* regs, float* slot) {
#ifdef __CUDA_ARCH__
    if (W % 4 == 0 && (reinterpret_cast<size_t>(slot) & 15u) == 0) {
        for (unsigned int w = 0; w < W; w += 4)
            *reinterpret_cast<float4*>(slot + w) = make_float4(regs[w], regs[w + 1], regs[w + 2], regs[w + 3]);
        return;
    }
#endif
    for (unsigned int w = 0; w < W; w++) slot[w] = regs[w];
}

template <unsigned int W>
DEME_HD_INLINE void storeZeroHistory(float* slot) {
    float zeros[W];
    for (unsigned int w = 0; w < W; w++) zeros[w] = 0.f;
    storeHistory<W>(zeros, slot);
}

// Whether a history is what clearing leaves: every float +0 (a -0 is stored over, so that skipping
// the store changes no bit of any later step).
template <unsigned int W>
DEME_HD_INLINE bool historyIsZero(const float* regs) {
    bool zero = true;
    for (unsigned int w = 0; w < W; w++) zero = zero && isPositiveZero(regs[w]);
    return zero;
}

// What one contact exerts: the force on A (B gets -force) and the torques about each owner's
// centre (global), and the two owners.
struct ContactLoad {
    float3 force, torqueA, torqueB;
    bodyID_t ownerA, ownerB;
};

// A contact's type not known to the caller (contactStepOfType), or known not to be a sphere and a
// triangle (a scene without meshes): the triangle's branch drops out of the path.
constexpr uint8_t ANY_CONTACT_TYPE = 0xFF;
constexpr uint8_t NO_TRIANGLE_CONTACT = 0xFE;

// What a contact's step reads first: its two geometries and, where the caller does not know it
// (KnownType below), its type (from B: state/ContactTypeOf.h). Apart from the rest, so that the
// GPU's pass can read them before its dependent launch's wait (no kernel of a step writes them;
// kernels/ForcePassKernel.cuh).
struct ContactIds {
    bodyID_t a, b;
    uint8_t type;
};

// A contact's ids from its two geometries (its type from B where the caller does not know it).
template <uint8_t KnownType, class S>
DEME_HD_INLINE ContactIds contactIdsOf(const S& s, bodyID_t a, bodyID_t b) {
    return ContactIds{a, b, KnownType < NO_TRIANGLE_CONTACT ? KnownType : contactTypeOf(s, b)};
}

// The same where the caller knows A (the CPU's set may keep A as runs: backend/cpu/ContactARuns.h).
template <uint8_t KnownType, class S>
DEME_HD_INLINE ContactIds contactIdsWithA(const S& s, size_t i, bodyID_t a) {
    return contactIdsOf<KnownType>(s, a, s.contacts.geomB[i]);
}

// (The GPU's force pass loads them before its wait and decodes A after: kernels/ForcePassKernel.cuh.)
template <uint8_t KnownType, class S>
DEME_HD_INLINE ContactIds contactIds(const S& s, size_t i) {
    return contactIdsWithA<KnownType>(s, i, pairAOf(s, i));
}

// Contact i's step, its ids read (contactIds) and its W history floats at `wc` (the set's own
// wildcards, or the CPU's copy of a pooled history: state/PooledHistory.h). Returns whether the
// pair touches (overlap > 0: a real contact); `applied` says whether `load` holds what it exerts
// (the model was called). `KnownType`: the contact's type where the caller knows it (the other
// geometry branches drop out of that path), else ANY_CONTACT_TYPE.
template <class Model, uint8_t KnownType, class S>
DEME_HD_INLINE bool contactStepWithHistory(S& s, const Model& model, size_t i, const ContactIds& ids, float* wc,
                                           const MeshStateAt& mesh, float time, float dt, bool& applied,
                                           ContactLoad& load) {
    constexpr bool SphereSphere = KnownType == SPHERE_SPHERE;
    auto& c = s.contacts;
    // The wildcard count is a constant of the model, so history loops unroll. A short history is
    // read once (after the gather: held across it, its registers would spill others), the model
    // works on that copy in registers, and it is stored once; a long one is worked on where it lies.
    constexpr unsigned int W = Model::kNumContactWildcards;
    constexpr bool kHistoryCopied = W > 0 && W <= MAX_COPIED_HISTORY;
    constexpr unsigned int WC = kHistoryCopied ? W : 1;  // the copy's size (never zero)
    float copied[WC];
    const uint8_t stored = KnownType < NO_TRIANGLE_CONTACT ? KnownType : ids.type;  // a constant where known
    const uint8_t type = KnownType == NO_TRIANGLE_CONTACT
                             ? (stored == SPHERE_SPHERE ? (uint8_t)SPHERE_SPHERE : (uint8_t)SPHERE_ANALYTICAL)
                             : stored;
    bool gather = type != SPHERE_TRIANGLE || (mesh.states[mesh.at] & 1u);
    if constexpr (DEME_VOXEL_PRETEST && !Model::kSeesApartPairs) {
        if ((SphereSphere || type == SPHERE_SPHERE) && s.voxelPretest)
            gather =
                !apartByVoxelCodes(s, ids.a, ids.b, (double)s.spheres.radius[ids.a] + (double)s.spheres.radius[ids.b]);
    }
    if (DEME_CENTRE_PRETEST && !Model::kSeesApartPairs && (SphereSphere || type == SPHERE_SPHERE)) {
        const double3 pA = sphereCentre(s, ids.a);
        const double3 d = pA - nearestImage(s.frame.periodic, pA, sphereCentre(s, ids.b));
        const double reach = (double)s.spheres.radius[ids.a] + (double)s.spheres.radius[ids.b];
        gather = dot(d, d) < reach * reach * (1.0 + 1e-9);
    }
    ContactInputs in;
    if (gather) gatherContactInputsOfType(s, ids.a, ids.b, type, time, dt, in);
    // A sphere of a parked clump (the "remove" exit policy, dynamics/OwnerStep.h) touches nothing.
    // It waits far beyond the domain, where no grain or mesh reaches -- but an analytical plane or
    // infinite cylinder does, and the sphere's overlap with one would be about a domain's length: a
    // load of meganewtons on the wall, in every step until the host takes the clump out.
    // (Read only where the model is to be called: one load more for a wall's real contacts alone.)
    if (type == SPHERE_ANALYTICAL && gather && (Model::kSeesApartPairs || in.overlapDepth > 0.0) &&
        (s.integrationScratch.flags[in.AOwner] & STEP_PARKED))
        gather = false;
    const bool touching = gather && in.overlapDepth > 0.0;
    applied = Model::kSeesApartPairs ? gather : touching;
    if (!applied) {
        // No call: no force, and the contact's history ends (stored only where some is left: most
        // pairs that do not touch have none, and the store is saved).
        if (kHistoryCopied) {
            loadHistory<WC>(wc, copied);
            if (!historyIsZero<WC>(copied)) storeZeroHistory<WC>(wc);
        } else {
            for (unsigned int w = 0; w < W; w++) wc[w] = 0.f;
        }
        return false;
    }
    float3 force = make_float3(0.f), torque_only_force = make_float3(0.f), couple_torque = make_float3(0.f);
    const bool wasPersistent = Model::kWritesPersistent && c.persistent[i] != 0;
    bool persistent = wasPersistent;
    if (kHistoryCopied) loadHistory<WC>(wc, copied);
    // A model that sees apart pairs is mostly called for pairs without a history that keep none
    // (most of a contact set's pairs are apart): their store is saved, as is an unchanged flag's.
    const bool historyWasZero = Model::kSeesApartPairs && kHistoryCopied && historyIsZero<WC>(copied);
    model(in, kHistoryCopied ? copied : wc, force, torque_only_force, couple_torque, persistent);
    if (kHistoryCopied && !(historyWasZero && historyIsZero<WC>(copied))) storeHistory<WC>(copied, wc);
    if (Model::kWritesPersistent && persistent != wasPersistent) c.persistent[i] = persistent ? 1 : 0;
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

// The same, with the history and mesh state where the set keeps them, per pair (the GPU's dense sets).
template <class Model, uint8_t KnownType, class S>
DEME_HD_INLINE bool contactStepOfType(S& s, const Model& model, size_t i, const ContactIds& ids, float time, float dt,
                                      bool& applied, ContactLoad& load) {
    constexpr unsigned int W = Model::kNumContactWildcards;
    float* wc = W ? &s.contacts.wildcards[i * W] : nullptr;
    return contactStepWithHistory<Model, KnownType>(s, model, i, ids, wc, MeshStateAt{s.contacts.meshState, i}, time,
                                                    dt, applied, load);
}

}  // namespace deme
