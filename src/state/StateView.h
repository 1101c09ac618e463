// The simulation state as flat arrays behind raw pointers: what GPU kernels get. Made from the same
// field lists as SimState (state/StateFields.h), so its members carry SimState's names and the
// per-item code (contact inputs, detection, owner step, force models) is written once as templates
// over the state type: SimState on the CPU, a StateView of device memory on the GPU. Plain data
// only, so NVRTC can compile it.
#pragma once

#include <deme/VariableTypes.h>

#include "physics/CompactPosition.h"
#include "state/CompactPairA.h"
#include "state/HistoryPool.h"
#include "state/StateFields.h"

namespace deme {

template <class T>
using ViewPointer = T*;

using OwnerView = OwnerFields<ViewPointer>;
using MassView = MassFields<ViewPointer>;
using SphereView = SphereFields<ViewPointer>;
using AnalyticalView = AnalyticalFields<ViewPointer>;
using TriangleView = TriangleFields<ViewPointer>;
// On the GPU `force` is null in the steps whose per-contact forces nobody reads: loads go to the
// owners directly there, and not writing them saves a third of the force pass's memory traffic.
using ContactView = ContactFields<ViewPointer>;
using CacheView = CacheFields<ViewPointer>;
using IntegrationScratchView = ScratchFields<ViewPointer>;

// The smallest set whose pairs the GPU's force pass turns away by their voxel codes (voxelPretest
// below; dynamics/ContactStep.h): a smaller one is held in the GPU's L2, where decoding a centre costs
// less than the test.
constexpr uint32_t VOXEL_PRETEST_MIN_PAIRS = 1u << 20;

struct StateView {
    DomainFrame frame;
    double3 domainSize;
    OwnerView owners;
    MassView massProps;
    SphereView spheres;
    AnalyticalView analytical;
    TriangleView triangles;
    ContactView contacts;
    // The set's As: compact on the GPU (state/CompactPairA.h; contacts.geomA is null there), whole
    // in a view of host arrays. Read through pairAOf.
    PairAList pairAs;
    HistoryPoolView historyPool;  // the GPU's pooled history (state/HistoryPool.h); slot null: none
    CacheView cache;
    IntegrationScratchView integrationScratch;
    unsigned int numWildcards;
    bool spheresAreOwners;  // as SimState's (state/SphereLayout.h)
    // The force pass turns sphere pairs away by their voxel codes before it decodes their centres
    // (dynamics/ContactStep.h, DEME_VOXEL_PRETEST): set by the GPU's dynamics for a large set of
    // mostly apart pairs; never read on the host.
    bool voxelPretest;
    uint32_t numOwners, numSpheres, numAnalytical, numTriangles;
    uint64_t numContacts;                     // a contact set may pass 2^32 pairs on the GPU
    uint32_t numClumps, numAnalyticalOwners;  // as SimState's: an owner's type (state/OwnerTypeOf.h)
    DEME_HD bodyID_t analyticalIdBase() const { return numSpheres; }
    DEME_HD bodyID_t triangleIdBase() const { return numSpheres + numAnalytical; }
};

// Pair i's A (SimState's: state/SimState.h).
DEME_HD_INLINE bodyID_t pairAOf(const StateView& s, size_t i) { return s.pairAs[i]; }

}  // namespace deme
