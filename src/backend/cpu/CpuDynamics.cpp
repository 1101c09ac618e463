#include "backend/cpu/CpuDynamics.h"

#include <algorithm>

#include "backend/cpu/CarriedPairs.h"
#include "backend/cpu/ContactARuns.h"
#include "backend/cpu/CpuKinematics.h"
#include "backend/cpu/ForcePass.h"
#include "backend/cpu/HistoryForm.h"
#include "backend/cpu/HistoryMapping.h"
#include "backend/cpu/Integration.h"
#include "backend/cpu/MeshContacts.h"
#include "dynamics/TravelSinceSnapshot.h"
#include "parallel/Parallel.h"
#include "runtime/AllocatorPolicy.h"
#include "runtime/MemoryAccounting.h"
#include "runtime/MemoryEstimate.h"

namespace deme {

CpuDynamics::CpuDynamics(SimState& s, CpuForceModel model, CpuKinematics& kinematics)
    : m_s(s), m_model(std::move(model)), m_kinematics(kinematics) {}

void CpuDynamics::upload(const SimState& /*s: the host state the steps run on*/, bool withContacts) {
    if (withContacts) m_chooseHistoryForm = true;
    if (withContacts) m_setTrimmed = false;
    // The steps run on the host state itself (its contacts too). (Its travel counts from the set in
    // use's snapshot: an upload is followed by a detection, which sets it back, or by a restart's
    // resumeContactSet, which keeps the checkpoint's.)
    releaseOrderBaseline();
    m_subsetStale = true;
    // The steps' flags start clear: the force pass reads an owner's (a parked clump touches nothing,
    // dynamics/ContactStep.h) before the first step has written any.
    m_s.integrationScratch.flags.assign(m_s.owners.size(), 0);
}

StepBatchResult CpuDynamics::steps(const StepBatchRequest& batch, const Settings& settings,
                                   const FamilyRules& families, TimingStats& timing) {
    StepBatchControl c = beginStepBatch(batch.time, settings.dt, batch.margin);
    StepBatchResult r;
    // A history a host reader, an edit or a restart left dense is pooled where that pays (an
    // installation chooses for its own set).
    // So is A (backend/cpu/ContactARuns.h): kept as runs again, or, where a reader or edit changed the
    // set, indexed again first (the step below does so where the index is empty).
    if (m_chooseHistoryForm) {
        chooseHistoryForm(m_s);
        keepPersistentFlagsWhereUsed(m_s.contacts, modelWritesPersistent());
        if (m_s.contacts.size() && contactAAsRunsAllowed(m_s) && !keepContactAAsRuns(m_s, false))
            m_s.contacts.resetIndex();
    }
    m_chooseHistoryForm = false;
    while (c.stepsDone < batch.maxSteps && !c.stop) {
        // Per-contact forces are kept by the step a call may end after (as on the GPU): every
        // pair's where most touched in the step before, else those of the pairs with a force.
        ForceStore store = ForceStore::NONE;
        if (batch.storeContactForcesAtEnd && c.stepsDone + 1 == batch.maxSteps)
            store = 4 * m_lastRealContacts > 3 * m_s.contacts.size() ? ForceStore::EVERY_PAIR
                                                                     : ForceStore::PAIRS_WITH_FORCE;
        r.last = step(c.time, settings, families, timing, store);
        finishBatchStep(c, tallyOf(r.last));
    }
    r.steps = c.stepsDone;
    r.time = c.time;
    r.realContactSum = c.realContactSum;
    return r;
}

StepOutcome CpuDynamics::step(double time, const Settings& settings, const FamilyRules& families, TimingStats& timing,
                              ForceStore store) {
    StepOutcome out;
    // The set's index, where a detection let it go and no installation followed (one that failed
    // its memory check: CpuDynamics::beforeDetectNow), or an edit did.
    if (m_s.contacts.ownerAStart.size() != m_s.owners.size() + 1) indexContactSet(m_s);
    // A sheared cell's image offset: the step's forces see the one at its start, its wrap the one at
    // its end (physics/Periodic.h); afterwards the state is at time + dt.
    m_s.frame.periodic.shearTime = time;
    {
        PhaseTimer t(timing, Phase::INTEGRATION);
        families.evaluate(time + settings.dt, m_stepMotion);
        if (m_subsetStale) m_subset.update(m_s, m_stepMotion);  // after a detection: O(owners)
        m_subsetStale = false;
    }
    {
        PhaseTimer t(timing, Phase::FORCE);
        resolveMeshContacts(m_s);
        const ForcePassResult r = m_model.pass(m_s, time, settings.dt, store);
        out.realContacts = m_lastRealContacts = r.realContacts;
        out.realSphereSphere = r.realSphereSphere;
    }
    {
        PhaseTimer t(timing, Phase::REDUCTION);
        reduceContactForces(m_s, m_subset);
    }
    PhaseTimer t(timing, Phase::INTEGRATION);
    const IntegrationResult ir =
        integrateOwners(m_s, m_stepMotion, settings.gravity, settings.dt, settings.errorOutVelocity,
                        settings.removeLeavingClumps, m_subset);
    m_s.frame.periodic.shearTime = time + settings.dt;
    out.maxSpeed = ir.maxSurfaceSpeed;
    out.maxTravel = ir.maxTravel;
    out.parkedOwners = ir.parkedOwners;
    if (ir.fault != OwnerFault::NONE) {
        out.fault = true;
        out.faultOwner = ir.faultOwner;
        out.faultFlags = m_s.integrationScratch.flags[ir.faultOwner];
    }
    return out;
}

void CpuDynamics::downloadContacts(SimState& s) {
    // Host readers get every pair's A and W floats of history (the steps' forms are made again
    // before the next step).
    if (s.contacts.aAsRuns) m_chooseHistoryForm = true;
    s.contacts.restoreA();
    if (s.contacts.persistent.size() != s.contacts.size()) {  // (none is set: ContactArrays::persistent)
        s.contacts.persistent.assign(s.contacts.size(), 0);
        m_chooseHistoryForm = true;
    }
    if (densifyHistory(s)) m_chooseHistoryForm = true;
}

void CpuDynamics::markOrderBaseline(bool installedBeforeNextStep) {
    // A synchronous detection's order is installed before any step: its snapshot is the travel
    // then, and no copy of 4 B per owner is held through the detection.
    m_orderAtInstall = installedBeforeNextStep;
    if (m_orderAtInstall)
        releaseOrderBaseline();
    else
        m_orderBaseline = m_s.owners.travel;
}

// The order's snapshot lives from the order to its installation (a synchronous detection's: within
// one call): let go between (4 B per owner) where it is a block of its own that goes back to the
// system (runtime/AllocatorPolicy.h); a smaller one stays in the heap either way. Made again at each
// order, it is a copy of the travel that writes all its pages anyway.
void CpuDynamics::releaseOrderBaseline() {
    if (vectorBytes(m_orderBaseline) >= LARGE_BLOCK_BYTES)
        releaseVector(m_orderBaseline);
    else
        m_orderBaseline.clear();
}

double CpuDynamics::maxTravelSinceOrder() {
    const std::vector<float>& travel = m_s.owners.travel;
    if (m_orderBaseline.size() != travel.size())
        throwError("DoDynamics", "internal: an order's travel is asked for with no order in flight");
    const float* atOrder = m_orderBaseline.data();
    const size_t n = travel.size();
    float m = 0.f;
#pragma omp parallel for simd reduction(max : m) if (n > PARALLEL_MIN_ITEMS)
    for (size_t o = 0; o < n; o++) m = std::max(m, travelSinceOrderSnapshot(travel[o], atOrder[o]));
    return m;
}

void CpuDynamics::install(const DetectionReport&, TimingStats& timing) {
    PhaseTimer t(timing, Phase::HISTORY_MAPPING);
    installDetectedContacts(m_s, m_kinematics.takenPairs(), modelWritesPersistent());
    // Travel counts from the new set's snapshot: the order's.
    std::vector<float>& travel = m_s.owners.travel;
    if (m_orderAtInstall) {
        std::fill(travel.begin(), travel.end(), 0.f);
    } else {
        if (m_orderBaseline.size() != travel.size())
            throwError("DoDynamics", "internal: a contact set is installed with no order's travel");
        const float* atOrder = m_orderBaseline.data();
        float* t = travel.data();
        const size_t n = travel.size();
#pragma omp parallel for simd if (n > PARALLEL_MIN_ITEMS)
        for (size_t o = 0; o < n; o++) t[o] = travelSinceOrderSnapshot(t[o], atOrder[o]);
    }
    m_orderAtInstall = false;
    releaseOrderBaseline();
    m_setTrimmed = false;
    m_subsetStale = true;  // the reduction's list (owners stepped or in a contact) follows the set
    // A large set's installation freed blocks in the heap's middle (runtime/AllocatorPolicy.h).
    if (m_s.contacts.size() * sizeof(bodyID_t) > KEEP_REBUILT_ARRAYS_UP_TO) returnFreedHeapPages();
}

bool CpuDynamics::beforeDetectNow() {
    // Trimmed while the index gives A (runs), then the index emptied (restoring A only where the
    // set was not trimmed). The share of the whole set's pairs with a history is kept for the
    // memory check before the installation (expectedHistorySlots).
    const double share = historyShare();
    if (keepOnlyCarriedPairs(m_s)) {
        m_historyShareBeforeTrim = share;
        m_setTrimmed = true;
    }
    m_s.contacts.resetIndex();
    return m_setTrimmed;
}

bool CpuDynamics::resumeContactSet(const SimState& s) {
    if (s.owners.travel.size() != s.owners.size()) return false;
    // The steps run on the host state, whose contact set is the restored one: only the bookkeeping
    // that an installation builds is missing.
    indexContactSet(m_s);
    m_chooseHistoryForm = true;
    m_setTrimmed = false;
    releaseOrderBaseline();
    return true;
}

std::string CpuDynamics::description() const { return "CPU, " + std::to_string(cpuThreadCount()) + " threads"; }

void CpuDynamics::countHostMemory(MemoryStats& m) const {
    addHost(m, MemoryGroup::OWNER_STATE, vectorBytes(m_orderBaseline));
    addHost(m, MemoryGroup::STEP_SCRATCH,
            vectorBytes(m_subset.owners) + vectorBytes(m_subset.spheres) + vectorBytes(m_subset.reduced));
}

void CpuDynamics::countRunMemory(size_t bytes[NUM_MEMORY_GROUPS]) const {
    MemoryStats held;
    countStateMemory(m_s, held);
    countHostMemory(held);
    for (int g = 0; g < NUM_MEMORY_GROUPS; g++) bytes[g] = held.hostBytes[g];
}

size_t CpuDynamics::memoryFree() const { return hostMemoryAvailable(); }

double CpuDynamics::historyShare() const {
    const ContactArrays& c = m_s.contacts;
    const unsigned int W = m_s.numWildcards;
    if (c.size() == 0) return 0.0;
    // A dense set is mapped dense (HistoryMapping.cpp): the installation's peak holds it so.
    if (W == 0 || !c.historyPooled(W)) return -1.0;
    return (double)(c.pooled.values.size() / W) / (double)c.size();
}

size_t CpuDynamics::expectedHistorySlots(size_t pairs, unsigned int W) const {
    if (W == 0) return DENSE_HISTORY;
    const double share = m_setTrimmed ? m_historyShareBeforeTrim : historyShare();
    if (share < 0.0) return DENSE_HISTORY;
    const size_t withHistory = (size_t)(share * (double)pairs + 0.5);
    return poolsHistory(pairs, withHistory) ? withHistory : DENSE_HISTORY;
}

size_t CpuDynamics::memoryAvailable() const {
    const size_t free = memoryFree();
    if (free == 0) return 0;
    MemoryStats held;
    countStateMemory(m_s, held);
    return free + held.hostTotal();
}

}  // namespace deme
