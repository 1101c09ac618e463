// The owners and spheres a GPU step integrates and places: all of them, or, with fixed owners at
// rest (the active box's dormant grains, docs/active-box.md), the others only, as the CPU's
// IntegrationSubset (backend/cpu/Integration.h) with the same rule (dynamics/OwnerStep.h,
// ownerAtRest) run by kernels/Dynamics.cu. A left-out owner's step would be itself, so the stepped
// owners' results do not change. With such a subset, the owners whose loads a step clears are also a
// subset: the stepped ones and those of some contact of the set (others get no load), listed again
// with each installed set; all loads are cleared once then, so that an owner that drops out of the
// list reads zero. Where no owner is at rest (most runs), a step needs no lists: then none is held
// (the flags and their sums alone would be 16 B per sphere), and where no family is fixed none is
// looked for either (no kernel, no wait for its answer at each call's start).
#include "backend/cuda/CudaDynamics.h"

namespace deme::cuda {

void CudaDynamics::updateStepSubset() {
    const Stream st = m_stream;
    const unsigned int nO = m_view.numOwners, nS = m_view.numSpheres;
    m_subsetStale = false;
    unsigned int anyAtRest = 0;
    if (m_anyFamilyFixed && nO) {
        if (m_anyOwnerAtRest.size() != 1) m_anyOwnerAtRest.resizeDiscarding(1);
        m_anyOwnerAtRest.zeroAsync(st);
        launch(kAnyOwnerAtRest, blocksFor(nO, 256), 256, 0, st, m_view, (const FamilyStepMotion*)m_motion.data(),
               m_anyOwnerAtRest.data());
        m_anyOwnerAtRest.downloadAsync(&anyAtRest, 1, st);
        synchronize(st);
    }
    if (!anyAtRest) {
        m_subsetAll = true;
        m_loadOwnersStale = false;
        for (DeviceBuffer<unsigned int>* b :
             {&m_ownerStepped, &m_ownerStepOffset, &m_sphereStepped, &m_sphereStepOffset})
            b->release();
        for (DeviceBuffer<bodyID_t>* b : {&m_steppedOwners, &m_steppedSpheres, &m_loadOwners}) b->release();
        return;
    }
    m_ownerStepped.resizeDiscarding(nO + 1);
    m_ownerStepOffset.resizeDiscarding(nO + 1);
    m_sphereStepped.resizeDiscarding(nS + 1);
    m_sphereStepOffset.resizeDiscarding(nS + 1);
    m_ownerStepped.zeroAsync(st);
    m_sphereStepped.zeroAsync(st);
    const unsigned int n = nO > nS ? nO : nS;
    if (n)
        launch(kSteppedFlags, blocksFor(n, 256), 256, 0, st, m_view, (const FamilyStepMotion*)m_motion.data(),
               m_ownerStepped.data(), m_sphereStepped.data());
    m_prim.exclusiveSum(m_ownerStepped.data(), m_ownerStepOffset.data(), nO + 1, st);
    m_prim.exclusiveSum(m_sphereStepped.data(), m_sphereStepOffset.data(), nS + 1, st);
    unsigned int owners = 0, spheres = 0;
    m_ownerStepOffset.downloadAsync(&owners, 1, st, nO);
    m_sphereStepOffset.downloadAsync(&spheres, 1, st, nS);
    synchronize(st);
    m_subsetAll = owners == nO;
    if (m_subsetAll) {
        m_loadOwnersStale = false;
        return;
    }
    m_numSteppedOwners = owners;
    m_numSteppedSpheres = spheres;
    m_steppedOwners.resizeDiscarding(owners);
    m_steppedSpheres.resizeDiscarding(spheres);
    launch(kSteppedScatter, blocksFor(n, 256), 256, 0, st, m_view, (const unsigned int*)m_ownerStepped.data(),
           (const unsigned int*)m_ownerStepOffset.data(), (const unsigned int*)m_sphereStepped.data(),
           (const unsigned int*)m_sphereStepOffset.data(), m_steppedOwners.data(), m_steppedSpheres.data());
    updateLoadOwners(false);
}

// The owners whose loads a step clears: the stepped ones and those of the set's contacts. After
// updateStepSubset the stepped owners' flags are at hand; after an install of a detected set only (the
// stepped owners are the same), they are set again from the list.
void CudaDynamics::updateLoadOwners(bool flagStepped) {
    const Stream st = m_stream;
    const unsigned int nO = m_view.numOwners;
    m_loadOwnersStale = false;
    if (m_subsetAll) return;  // every owner's loads are cleared
    if (flagStepped) {
        m_ownerStepped.zeroAsync(st);
        if (m_numSteppedOwners)
            launch(kFlagListed, blocksFor(m_numSteppedOwners, 256), 256, 0, st,
                   (const bodyID_t*)m_steppedOwners.data(), m_numSteppedOwners, m_ownerStepped.data());
    }
    if (m_numContacts)
        launch(kMarkContactOwners, blocksFor(m_numContacts, 256), 256, 0, st, m_view, m_ownerStepped.data());
    m_prim.exclusiveSum(m_ownerStepped.data(), m_ownerStepOffset.data(), nO + 1, st);
    unsigned int cleared = 0;
    m_ownerStepOffset.downloadAsync(&cleared, 1, st, nO);
    synchronize(st);
    m_numLoadOwners = cleared;
    m_loadOwners.resizeDiscarding(cleared);
    launch(kScatterFlagged, blocksFor(nO, 256), 256, 0, st, (const unsigned int*)m_ownerStepped.data(),
           (const unsigned int*)m_ownerStepOffset.data(), nO, m_loadOwners.data());
    m_state.owners.contactForce.zeroAsync(st);
    m_state.owners.contactTorque.zeroAsync(st);
}

}  // namespace deme::cuda
