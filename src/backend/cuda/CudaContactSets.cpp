// CudaDynamics' contact sets: the snapshot an order is measured from, whether a delivered set may
// still serve, and the installation of a detected set with the history of the one it replaces
// (ARCHITECTURE.md invariant 6): persistent pairs merged back, wildcards and mesh state mapped by
// key, family initial values for new pairs.
#include <chrono>
#include <cstring>

#include "backend/cuda/CudaDynamics.h"
#include "backend/cuda/CudaKinematics.h"

namespace deme::cuda {

namespace {

constexpr unsigned int THREADS = 256;

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

void CudaDynamics::markOrderBaseline(bool installedBeforeNextStep) {
    select();
    // A synchronous detection's set is installed before any step: its snapshot is the travel then,
    // which the installation sets to zero, and no copy (4 B per owner) is held; a large one left
    // from an asynchronous order goes (as the CPU's).
    m_orderAtInstall = installedBeforeNextStep;
    if (m_orderAtInstall) {
        if (m_orderBaseline.capacityBytes() > m_smallSetBytes) m_orderBaseline.release();
        return;
    }
    // The owners' travel now: the set an order sent now yields serves while nobody travels its margin
    // beyond it.
    m_orderBaseline.resizeDiscarding(m_view.numOwners);
    if (m_view.numOwners) m_orderBaseline.copyFromAsync(m_state.owners.travel, m_view.numOwners, m_stream);
}

double CudaDynamics::maxTravelSinceOrder() {
    select();
    m_maxTravelBits.zeroAsync(m_stream);
    launch(kMaxTravelSince, blocksFor(m_view.numOwners, THREADS), THREADS, 0, m_stream,
           (const float*)m_state.owners.travel.data(), (const float*)m_orderBaseline.data(), m_view.numOwners,
           m_maxTravelBits.data());
    unsigned long long bits = 0;
    m_maxTravelBits.downloadAsync(&bits, 1, m_stream);
    synchronize(m_stream);
    double t;
    std::memcpy(&t, &bits, sizeof(double));
    return t;
}

// Before a synchronous detection the set in use keeps only the pairs that hand something to the
// next set (DeviceHistoryMapping::keepOnlyPairsHandedOn): the installation's peak then holds the
// fresh set and those, not two whole sets. A trimmed set's per-contact forces (which follow its
// pairs) are let go first: nothing reads them before the installation replaces them. The share of
// its pairs with a slot is kept for the memory check before that installation.
bool CudaDynamics::beforeDetectNow() {
    if (!trimsBeforeDetection(m_numContacts)) return m_setTrimmed;
    select();
    size_t n = m_numContacts;
    const auto releaseForces = [this] {
        m_pairsForSlotShare = m_numContacts;
        returnForceMemory();
        m_contacts[m_current].force.release();
    };
    if (m_history.keepOnlyPairsHandedOn(m_contacts[m_current], m_pools[m_current], n, m_W, m_prim, m_stream,
                                        releaseForces)) {
        m_numContacts = n;
        m_setTrimmed = true;
        m_loadOwnersStale = true;
        refreshView();
    }
    return m_setTrimmed;
}

// The idle set's wildcards hold the history of the set before the one in use: dead until the next
// install maps into them. Per-contact forces (12 B a pair), written by a storing step and read by
// the host before the next install, live there meanwhile, so they take no memory of their own where
// the model keeps at least three wildcards a pair (Hertz-Mindlin keeps four).
void CudaDynamics::lendIdleMemoryToForces() {
    DeviceContacts& inUse = m_contacts[m_current];
    if (historyPooled()) {
        // A pooled set keeps its forces per slot (state/HistoryPool.h), in memory of their own: the
        // idle set's pool is small, and gone once mapped.
        inUse.force.resizeDiscarding(m_pools[m_current].capacity);
        refreshView();
        return;
    }
    if (!m_forcesInIdleMemory) {
        inUse.force.release();  // forces uploaded with the set: a storing step rewrites them all
        inUse.force.tradeMemory(m_contacts[1 - m_current].wildcards);
        m_forcesInIdleMemory = true;
    }
    inUse.force.resizeDiscarding(m_numContacts);  // grows the lent memory where it is too small
    refreshView();
}

void CudaDynamics::returnForceMemory() {
    if (!m_forcesInIdleMemory) return;
    m_contacts[1 - m_current].wildcards.tradeMemory(m_contacts[m_current].force);
    m_forcesInIdleMemory = false;
    refreshView();
}

// History mapping from the set in use (with its up-to-date wildcards) into the fresh one, then the
// fresh one serves.
void CudaDynamics::install(const DetectionReport& r, TimingStats& timing) {
    select();
    const double t0 = now();
    returnForceMemory();  // the fresh set's wildcards take the mapped history
    DeviceContacts& old = m_contacts[m_current];
    DeviceContacts& fresh = m_contacts[1 - m_current];
    // The outbox's buffers become the fresh set's pairs. The fresh set's former ones (dead since
    // the set before) are let go before the fresh set's history is made: the installation's peak
    // holds two sets, not a third set of pairs (8 B a pair).
    KinematicsOutbox& out = m_kinematics->outbox();
    std::swap(fresh.pairA, out.pairA);
    std::swap(fresh.geomB, out.geomB);
    out.pairA.release();
    out.geomB.release();
    // Persistent pairs the detection missed stay in the set; every pair takes its history over.
    const MemoryGroupScope group(MemoryGroup::CONTACTS);  // history mapping's scratch
    HistoryPoolPolicy policy = m_poolPolicy;
    policy.W = m_W;
    uint32_t slotsUsed = 0;
    const size_t total = m_history.install(fresh, m_pools[1 - m_current], r.numPairs, old, m_pools[m_current],
                                           m_numContacts, m_W, policy, m_view, m_prim, m_stream, slotsUsed);
    // Per-contact forces are written by a storing step of the set in use only (nothing carries them
    // from one set to the next), in memory lent for it then.
    old.force.release();
    // Once mapped, the old set's pairs and flags are dead until it is the fresh set of the next
    // installation, which sizes them anew: its pairs' buffers become the outbox, which kT fills at
    // the next order (issued after this returns; kT resizes it there before it writes), and its
    // flags are let go. Its wildcards stay: they hold the per-contact forces of storing steps
    // (lendIdleMemoryToForces) and the next set's history. Between installations a run then holds
    // the set in use, the outbox's pairs and the idle wildcards: 50 B a pair with Hertz-Mindlin's
    // four wildcards, where it held 60.
    synchronize(m_stream);  // the mapping has read them
    std::swap(out.pairA, old.pairA);
    std::swap(out.geomB, old.geomB);
    // Where detection is synchronous, nobody writes the outbox before the next detection, which
    // sizes it anew: a large one is let go (8 B a pair between installations; a small one is kept,
    // m_smallSetBytes).
    if (!m_asyncDetection && out.geomB.capacity() * sizeof(bodyID_t) > m_smallSetBytes) {
        out.pairA.release();
        out.geomB.release();
    }
    old.persistent.release();
    old.meshState.release();
    m_pools[m_current].release();  // a pooled old set's slots and pool are read; no forces live there
    m_current = 1 - m_current;
    m_numContacts = total;
    m_pairsForSlotShare = total;
    m_setTrimmed = false;
    m_installs++;
    if (historyPooled()) {
        m_pooledInstalls++;
        resetHistoryPoolControl(slotsUsed);
    }
    refreshView();
    // The set's snapshot is the order's: travel counts from there (a synchronous order's is now).
    if (m_orderAtInstall)
        m_state.owners.travel.zeroAsync(m_stream);
    else
        launch(kTravelSinceOrder, blocksFor(m_view.numOwners, THREADS), THREADS, 0, m_stream,
               (float*)m_state.owners.travel.data(), (const float*)m_orderBaseline.data(), m_view.numOwners);
    m_orderAtInstall = false;
    // The owners whose loads a step clears follow the set's contacts. Which owners are stepped does
    // not change with a set (only uploads and family changes, which flag m_subsetStale themselves).
    m_loadOwnersStale = true;
    synchronize(m_stream);
    timing.seconds[(int)Phase::HISTORY_MAPPING] += now() - t0;
}

}  // namespace deme::cuda
