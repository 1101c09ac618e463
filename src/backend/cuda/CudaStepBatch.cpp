// CudaDynamics' steps, in batches (dynamics/StepBatch.h): one step's kernels are written down once
// as a launch list and replayed for the steps of the batch from CUDA graphs (StepGraph.h); the
// step's time, size and the rule that ends a batch early live in a control block in device memory,
// so nothing in the replayed step changes from one step to the next. The host synchronises once per
// batch, when it reads the control block back.
#include <algorithm>
#include <chrono>
#include <string>

#include <cuda_runtime_api.h>
#include <deme/Error.h>

#include "backend/cuda/CudaCheck.h"
#include "backend/cuda/CudaDynamics.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/StepGraph.h"
#include "dynamics/OwnerStep.h"

namespace deme::cuda {

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

void CudaDynamics::recordStep(LaunchList& list, const Settings& settings, bool storeContactForces, bool afterPass) {
    list.clear();
    list.overlapLaunches(m_overlapLaunches);
    const unsigned int nO = m_view.numOwners, nT = m_view.numTriangles;
    const auto& loads = m_state.trackerLoads;
    const bool withLoads = loads.extraAcc.size() == nO;
    const StepConstants consts{settings.gravity,
                               (float)settings.dt,
                               settings.dt,
                               settings.errorOutVelocity * settings.errorOutVelocity,
                               m_view.frame,
                               m_view.domainSize,
                               withLoads ? loads.extraAcc.data() : nullptr,
                               withLoads ? loads.extraAngAcc.data() : nullptr,
                               settings.removeLeavingClumps};
    const StepBatchControl* ctl = m_control.data();
    const bodyID_t* ownerIds = m_subsetAll ? nullptr : m_steppedOwners.data();
    const bodyID_t* sphereIds = m_subsetAll ? nullptr : m_steppedSpheres.data();
    const unsigned int nStepped = m_subsetAll ? nO : m_numSteppedOwners;
    // Spheres that are their owners are placed with them (state/SphereLayout.h).
    const unsigned int nPlaced = m_view.spheresAreOwners ? 0 : m_subsetAll ? m_view.numSpheres : m_numSteppedSpheres;
    StepReduction* red = m_reduction.data();
    StateView stepView = m_view;
    if (!storeContactForces) stepView.contacts.force = nullptr;

    // The force phase runs from the end of the step before (or the batch's start) to integration
    // (which adds the phase's length to the control block). The step's force pass finds the loads
    // cleared by the integration before it (or by the batch's first kernel, steps()); in the active
    // box and in large scenes (loadsClearedByIntegration) the step's first kernel clears them, and
    // the phase starts there.
    const bool clearedByIntegration = m_subsetAll && loadsClearedByIntegration(nO);
    if (!clearedByIntegration && !afterPass) {
        const bodyID_t* clearIds = m_subsetAll ? nullptr : m_loadOwners.data();
        const unsigned int nCleared = m_subsetAll ? nO : m_numLoadOwners;
        const unsigned int tCleared = stepThreadsFor(nCleared);
        list.kernel(kClearLoads, std::max(1u, blocksFor(nCleared, tCleared)), tCleared, 0, m_control.data(),
                    m_state.owners.contactForce.data(), m_state.owners.contactTorque.data(), clearIds, nCleared);
    }
    // A storing step's loads stay for the host to read (trackers); the next batch's first kernel
    // clears them.
    const unsigned int clearLoads = clearedByIntegration && !storeContactForces ? 1u : 0u;
    const unsigned int tMesh = stepThreadsFor(m_numContacts);
    if (!afterPass) {
        if (nT && m_numContacts) list.kernel(kResolveMesh, blocksFor(m_numContacts, tMesh), tMesh, 0, m_view, ctl, red);
        const unsigned int tForce = settings.threadsPerBlock ? settings.threadsPerBlock : stepThreadsFor(m_numContacts);
        m_model.record(list, stepView, ctl, m_view.numClumps, nO - m_view.numClumps, red, tForce);
    }
    // Contact forces were summed onto every owner (dormant ones too: trackers read them); only the
    // stepped owners are integrated and placed. Right after a force pass, which writes none of an
    // owner step's inputs but its loads, the integration reads them before it waits for the pass
    // (kernels/Dynamics.cu, startOwnerStep).
    const unsigned int tStepped = stepThreadsFor(nStepped);
    const unsigned int inputsBeforeWait = m_inputsBeforeWait && stepView.numContacts > 0 && !afterPass ? 1u : 0u;
    if (m_fusedStep && nT == 0) {
        // At least one block: it also ends the step. Where every owner is stepped, owner o is
        // thread o, so the analytical owners (after the clumps) are one block's where their ids
        // share a block: that block places their components.
        const unsigned int firstBlock = m_view.numClumps / tStepped;
        const bool oneBlock = m_subsetAll && m_view.numAnalyticalOwners > 0 && m_analyticalInBlock &&
                              (m_view.numClumps + m_view.numAnalyticalOwners - 1) / tStepped == firstBlock;
        list.kernel(kIntegrateAndPlace, std::max(1u, blocksFor(nStepped, tStepped)), tStepped, 0, m_view,
                    m_control.data(), (const FamilyStepMotion*)m_motion.data(), consts, ownerIds, nStepped,
                    inputsBeforeWait, clearLoads, (const uint32_t*)m_ownerSphereStart.data(), m_view.numClumps,
                    m_view.numAnalyticalOwners, oneBlock ? firstBlock : NO_ANALYTICAL_BLOCK, m_domainDiagonal, red,
                    m_componentSpeed.data(), m_blocksDone.data());
        return;
    }
    list.kernel(kIntegrate, blocksFor(nStepped, tStepped), tStepped, 0, m_view, m_control.data(),
                (const FamilyStepMotion*)m_motion.data(), consts, ownerIds, nStepped, inputsBeforeWait, clearLoads,
                red);
    // At least one block: it also ends the step.
    const unsigned int tPlaced = stepThreadsFor((unsigned long long)nPlaced + nT);
    const unsigned int placeBlocks = std::max(1u, blocksFor((unsigned long long)nPlaced + nT, tPlaced));
    list.kernel(kPlaceAndFinish, placeBlocks, tPlaced, 0, m_view, m_control.data(), sphereIds, nPlaced, nT,
                m_view.numClumps, m_view.numAnalyticalOwners, (float)settings.dt, m_domainDiagonal, red,
                m_componentSpeed.data(), m_blocksDone.data());
}

StepBatchResult CudaDynamics::steps(const StepBatchRequest& batch, const Settings& settings, const FamilyRules&,
                                    TimingStats& timing) {
    const Stream st = m_stream;
    const unsigned long long n = std::max<unsigned long long>(batch.maxSteps, 1);
    if (n > MAX_BATCH_STEPS)  // the prescriptions' table holds that many steps
        throwError("DoDynamics", "a batch of " + std::to_string(n) + " steps; at most " +
                                     std::to_string(MAX_BATCH_STEPS) + " go in one");
    if (m_profileFromStep >= m_steps && m_profileFromStep < m_steps + n) startProfilerCapture();
    m_steps += n;
    const double t0 = now();
    StepBatchControl* ctl = m_control.data();
    launch(kBeginBatch, 1, 1, 0, st, ctl, batch.time, settings.dt, batch.margin, m_reduction.data());
    // The prescriptions of each of the batch's steps (codegen/FamilyMotionSource.h), and, where
    // integration clears the loads, every owner's cleared for the first step (the step before may
    // have kept them for the host). Where a kernel clears them at every step's start, the batch
    // leaves them: a scene that large (loadsClearedByIntegration) never has integration clear them,
    // in the active box or not, and clearing its millions of owners twice would cost a sweep.
    const unsigned int nO = m_view.numOwners, tableSize = (unsigned int)n * NUM_FAMILIES;
    const unsigned int nCleared = loadsClearedByIntegration(nO) ? nO : 0u;
    launch(kFamilyMotion, blocksFor(std::max(tableSize, nCleared), 256), 256, 0, st, (const StepBatchControl*)ctl,
           m_motion.data(), (unsigned int)n, m_state.owners.contactForce.data(), m_state.owners.contactTorque.data(),
           nCleared);
    if (m_subsetStale) {
        // After an upload, a detection or a family change: O(owners), reads the first step's motion.
        updateStepSubset();
    } else if (m_loadOwnersStale) {
        updateLoadOwners(true);
    }
    if (historyPooled()) makeHistoryRoomBeforeBatch();
    if (batch.storeContactForcesAtEnd) lendIdleMemoryToForces();
    recordStep(m_plainStep, settings, false);
    if (batch.storeContactForcesAtEnd) recordStep(m_storingStep, settings, true);
    // The batch's steps: the last one stores the contact forces if asked; the plain ones go in
    // graphs of m_graphSteps steps, then one a graph.
    const unsigned long long plain = batch.storeContactForcesAtEnd ? n - 1 : n;
    if (m_useGraphs) {
        unsigned long long k = 0;
        if (m_graphSteps > 1)
            for (; k + m_graphSteps <= plain; k += m_graphSteps) m_plainGraphs.launch(m_plainStep, st, m_graphSteps);
        for (; k < plain; k++) m_plainGraph.launch(m_plainStep, st);
        if (plain < n) m_storingGraph.launch(m_storingStep, st);
    } else {
        for (unsigned long long k = 0; k < n; k++) (k < plain ? m_plainStep : m_storingStep).enqueue(st);
    }
    m_control.downloadAsync(m_controlHost, 1, st);
    if (historyPooled()) m_poolControl.downloadAsync(&m_poolControlHost, 1, st);
    synchronize(st);
    // A step whose force pass found the pool full stopped before its integration: finished here.
    if (historyPooled() && m_poolControlHost.paused)
        finishPausedStep(settings, batch.storeContactForcesAtEnd && m_controlHost->stepsDone + 1 == n);
    const StepBatchControl c = *m_controlHost;
    if (c.stepsDone) m_lastRealContacts = c.last.realContacts;

    // The force phases' device time, summed over the batch's steps by the kernels themselves.
    const double batchSeconds = now() - t0;
    const double forceSeconds = std::min(batchSeconds, 1e-9 * (double)c.forcePhaseNs);
    timing.seconds[(int)Phase::FORCE] += forceSeconds;
    timing.seconds[(int)Phase::INTEGRATION] += batchSeconds - forceSeconds;

    StepBatchResult r;
    r.steps = c.stepsDone;
    r.time = c.time;
    r.realContactSum = c.realContactSum;
    r.last = outcomeOf(c.last);
    if (r.last.fault) {
        m_state.integrationScratch.flags.downloadAsync(&r.last.faultFlags, 1, st, c.last.firstFault);
        synchronize(st);
    }
    return r;
}

std::string CudaDynamics::launchReport() const {
    const std::string history = "; contact history pooled in " + std::to_string(m_pooledInstalls) + " of " +
                                std::to_string(m_installs) + " installed sets, " + std::to_string(m_historyPauses) +
                                " steps paused to grow a pool";
    const std::string overlap =
        std::string(m_overlapLaunches ? ", each kernel overlapping the drain of the one before"
                                      : ", each kernel after the one before has ended") +
        (m_fusedStep && m_view.numTriangles == 0 ? ", integration and placement in one kernel" : "") +
        (m_subsetAll && loadsClearedByIntegration(m_view.numOwners) ? ", loads cleared by integration"
                                                                     : ", loads cleared by a kernel a step");
    if (!m_useGraphs) return "steps launched kernel by kernel (DEME_CUDA_GRAPHS=0)" + overlap + history;
    const unsigned long long made = m_plainGraph.captures() + m_plainGraphs.captures() + m_storingGraph.captures();
    const unsigned long long updated = m_plainGraph.updates() + m_plainGraphs.updates() + m_storingGraph.updates();
    return "steps replayed from CUDA graphs of up to " + std::to_string(m_graphSteps) +
           " steps: " + std::to_string(made) + " captured (" + std::to_string(updated) + " of them updated in place, " +
           std::to_string(made - updated) + " instantiated)" + overlap + history;
}

}  // namespace deme::cuda
