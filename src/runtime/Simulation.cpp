#include "runtime/Simulation.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <type_traits>

#include <deme/Error.h>

#include "dynamics/ContactInputsGather.h"
#include "dynamics/KinematicCache.h"
#include "dynamics/MeshContactRule.h"
#include "dynamics/OwnerStep.h"
#include "kinematics/BinGridSizing.h"
#include "kinematics/CarriedPairsRule.h"
#include "parallel/Parallel.h"
#include "runtime/IndexLimits.h"
#include "runtime/MemoryAccounting.h"
#include "runtime/PeriodicLimits.h"
#include "runtime/RebuiltArrays.h"
#include "state/SphereLayoutChoice.h"
#include "state/SphereIds.h"

namespace deme {

void Simulation::log(Verbosity level, const std::string& msg) const {
    if (settings.verbosity < level) return;
    std::ostream& os = level <= Verbosity::WARNING ? std::cerr : std::cout;
    os << (level == Verbosity::ERROR     ? "[deme] error: "
           : level == Verbosity::WARNING ? "[deme] warning: "
                                         : "[deme] ")
       << msg << std::endl;
}

namespace {

// Where a run's steps keep their arrays, for the memory errors: "GPU 0 (NVIDIA H200) memory" or
// "host memory".
std::string memoryPlace(const DynamicsBackend& d) { return d.onGpu() ? d.description() + " memory" : "host memory"; }

}  // namespace

Simulation::Simulation() = default;
Simulation::~Simulation() = default;

void Simulation::start(SimState&& state, const ModelLayout& model) {
    checkPeriodicScene(state, "Initialize");
    m_state = std::move(state);
    m_state.frame.parks = settings.removeLeavingClumps;  // (allowParking)
    m_model = model;
    m_initialScene = sceneFingerprint(m_state, m_model);  // (the same in either sphere layout)
    chooseSphereLayout(m_state);
    shareSphereIdsWithOwners(m_state);
    refreshKinematicCache(m_state);
    m_grid = makeBinGrid(m_state, settings.binSize);
    checkShearedGrid(m_state.frame.periodic, m_grid, "Initialize");
    applyDetectionMode();
    m_backends = makeBackends(m_state, m_model, settings, [this](Verbosity v, const std::string& msg) { log(v, msg); });
    // The CPU's steps run on the host state, results included; a GPU's upload makes its own.
    if (!m_backends.dynamics->onGpu()) m_state.owners.makeResults();
    // A scene too large for the memory its steps use fails here, not in its first detection.
    const DynamicsBackend& dynamics = *m_backends.dynamics;
    const KinematicsBackend& kinematics = *m_backends.kinematics;
    m_memoryEstimate = estimateRunMemory(
        m_state, m_grid, dynamics.onGpu(), kinematics.mayBinSpheresByCentre(m_state.spheres.size()),
        settings.asyncDetection || !kinematics.detectsInPlace(), 0,
        [this](size_t pairs) { return contactSetForm(pairs); }, keepRebuiltArraysUpTo("Initialize"));
    requireMemoryFor(m_memoryEstimate, dynamics.memoryAvailable(), memoryPlace(dynamics), "Initialize");
    // So is a scene whose pairs would pass what the backend's pair indices address: 32 bits on the
    // CPU, a GPU set's bound otherwise (runtime/IndexLimits.h).
    if (dynamics.onGpu())
        requireGpuPairCount(m_memoryEstimate.pairs, "Initialize");
    else
        requireIndexable(m_memoryEstimate.pairs, "contact pairs assumed (6 a sphere)", TOO_MANY_SPHERES_REMEDY,
                         "Initialize");
    m_contacts.start(settings, *m_backends.dynamics, *m_backends.kinematics);
    m_contacts.period = &m_state.frame.periodic;
    // A contact set larger than the memory holds is an error naming it, before it is installed.
    m_contacts.beforeInstall = [this](size_t pairs) {
        const DynamicsBackend& d = *m_backends.dynamics;
        size_t held[NUM_MEMORY_GROUPS] = {};
        d.countRunMemory(held);
        requireRoomForContactSet(
            pairs, contactSetBytes(m_state, d.onGpu(), pairs, contactSetForm(pairs)),
            held, [&d] { return d.memoryFree(); }, memoryPlace(d), "DoDynamics");
    };
    // ChangeFamilyWhen is checked at each detection (docs/active-box.md says why).
    m_contacts.beforeDetection = [this] {
        if (!families.conditions().empty()) m_backends.dynamics->applyFamilyConditions(m_time, families);
    };
    m_backendStale = m_backendContactsStale = true;
    m_hostStale = m_hostContactsStale = false;
    m_initialized = true;
    log(Verbosity::INFO, "initialized: " + std::to_string(m_state.numClumps) + " clumps, " +
                             std::to_string(m_state.spheres.size()) + " spheres, " +
                             std::to_string(m_state.analytical.size()) + " analytical components; bin size " +
                             std::to_string(m_grid.size) + " (" + std::to_string(m_grid.numBins()) +
                             " bins); dynamics on " + backendDescription() + ", contact detection " +
                             (settings.asyncDetection ? "beside it (asynchronous)" : "on the dynamics side"));
}

ContactSetForm Simulation::contactSetForm(size_t pairs) const {
    ContactSetForm f;
    f.historySlots = m_backends.dynamics->expectedHistorySlots(pairs, m_state.numWildcards);
    f.lateSlots = m_backends.dynamics->expectedLateSlots(pairs, m_state.numWildcards);
    f.trimmedBeforeDetection = !settings.asyncDetection &&
                               mayKeepOnlyPairsHandedOn(!m_state.wildcards.contactInit.empty()) &&
                               m_backends.dynamics->trimsBeforeDetection(pairs);
    f.persistentFlags = !m_model.builtIn() || m_backends.dynamics->keepsPersistentFlags();
    return f;
}

void Simulation::applyDetectionMode() {
    // Measured (BENCHMARKS.md): on 2 cores the kinematics thread takes more from the dynamics team
    // than it saves; with 8 or more, giving it one core hides detection.
    const int cores = cpuCoreCount();
    const Settings::DetectionMode mode = settings.detectionMode;
    settings.asyncDetection =
        mode == Settings::DetectionMode::ASYNC || (mode == Settings::DetectionMode::AUTO && cores >= ASYNC_MIN_CORES);
    // Detection gets a quarter of the cores (at least one), dynamics the rest, unless the user chose
    // the team size.
    settings.kinematicsThreads = std::max(1, cores / 4);
    if (settings.asyncDetection && settings.cpuThreads == 0 && !std::getenv("OMP_NUM_THREADS"))
        setCpuThreadCount(std::max(1, cores - settings.kinematicsThreads));
}

const SimState& Simulation::state() const {
    if (m_hostStale) {
        m_backends.dynamics->download(m_state);
        m_hostStale = false;
    }
    return m_state;
}

const SimState& Simulation::stateWithContacts() const {
    state();
    if (m_hostContactsStale) {
        m_backends.dynamics->downloadContacts(m_state);
        m_hostContactsStale = false;
    }
    return m_state;
}

const SimState& Simulation::wholeState() const {
    stateWithContacts();
    // (A GPU run's host lets them go after each upload and each call's steps.)
    if (!m_state.owners.holdsResults()) m_backends.dynamics->downloadResults(m_state);
    return m_state;
}

SimState& Simulation::editState() {
    state();
    m_backendStale = true;
    return m_state;
}

SimState& Simulation::editStateWithContacts() {
    stateWithContacts();
    m_backendStale = m_backendContactsStale = true;
    return m_state;
}

SimState& Simulation::editWholeState() {
    wholeState();
    m_backendStale = m_backendContactsStale = true;
    return m_state;
}

void Simulation::ownerLoads(const std::vector<bodyID_t>& owners, float3* force, float3* torque) const {
    const SimState& s = state();
    if (!s.owners.holdsResults()) {
        m_backends.dynamics->gatherOwnerLoads(owners, force, torque);
        return;
    }
    for (size_t i = 0; i < owners.size(); i++) {
        if (force) force[i] = s.owners.contactForce[owners[i]];
        if (torque) torque[i] = s.owners.contactTorque[owners[i]];
    }
}

void Simulation::markHostBehind() {
    if (!m_backends.dynamics->onGpu()) {
        // The CPU steps the host state itself; only the contacts' history may be in the steps'
        // pooled form (backend/cpu/HistoryForm.h), which a reader of the set has made dense.
        if (!m_backendContactsStale) m_hostContactsStale = true;
        return;
    }
    m_hostStale = true;
    // The owners' results are fetched again where asked for (wholeState), not kept behind.
    m_state.owners.releaseResults();
    // Contacts the host edited and has not sent yet stay until the upload that sends them.
    if (m_backendContactsStale) return;
    m_hostContactsStale = true;
    forEachContactField(m_state.contacts, m_state.contacts,
                        [](auto& field, auto&, FieldRole) { releaseVector(field); });
}

void Simulation::allowParking() {
    // Once on, for the solver's life: a parked clump's centre is read wherever a centre is (the
    // backends' views and kT's copy take the frame with the next upload), and turning it off
    // again would gain a few per cent for a rule that is easy to get wrong.
    if (settings.removeLeavingClumps && !m_state.frame.parks) editState().frame.parks = true;
}

void Simulation::uploadIfEdited() {
    if (!m_backendStale) return;
    // The order in flight was detected from the state being replaced: let it finish unseen, so the
    // kinematics side is idle while its geometry changes.
    m_contacts.dropOrderInFlight();
    settings.maxMargin = periodicMarginCap(m_state, settings.familyExtraMargin);
    // (the GPU's upload makes dT's GPU current for what follows)
    m_backends.dynamics->upload(m_state, m_backendContactsStale);
    m_backendContactsStale = false;
    m_backends.kinematics->setGeometry(m_state, m_grid, families, settings);
    m_contacts.invalidate();
    // After a restart: go on with the restored set where the backend can (Simulation::restore).
    if (m_resume && m_resume->contactSetResumable && m_backends.dynamics->resumeContactSet(m_state))
        m_contacts.resume(m_resume->contactSet);
    m_resume.reset();
    m_backendStale = false;
    // A GPU run's host keeps no copy of the owners' results (state/SimState.h): the device has them.
    if (m_backends.dynamics->onGpu()) m_state.owners.releaseResults();
}

namespace {

// Asynchronous detection, with an order in flight: steps between looks for its result. A result
// taken up to this many steps late only raises the latency n_max adapts to; looking every step
// would cost a GPU one host synchronisation per step.
constexpr unsigned int ASYNC_POLL_STEPS = 16;

// Parked clumps (the "remove" exit policy) wait in one border bin, where each detection compares
// them pairwise: past this many the host removes them before the call's end.
constexpr size_t PARKED_CLUMPS_REMOVED_AT = 512;

}  // namespace

// The engine's one step loop, on either backend: steps run in batches (dynamics/StepBatch.h) between
// the points where the host must look -- the contact-set schedule's decisions, the monitor's polls,
// the call's end -- and a batch ends early after a step that lets the set in use expire or faults.
void Simulation::advance(unsigned long long n) {
    m_monitor.begin(n, m_time, settings.dt, m_state.spheres.size());
    CollaborationStats& collab = m_contacts.stats();
    DynamicsBackend& dynamics = *m_backends.dynamics;
    const auto t0 = std::chrono::steady_clock::now();
    allowParking();
    uploadIfEdited();
    const bool loads = !m_state.trackerLoads.empty();
    if (loads) dynamics.uploadTrackerLoads(m_state);
    dynamics.beginRun(settings, families);
    size_t parked = 0;  // clumps parked after the last batch
    for (unsigned long long k = 0; k < n;) {
        m_state.frame.periodic.shearTime = m_time;  // the host state's time (a sheared cell's offset)
        // A contact set serves at most n_max steps, and only while nobody has travelled its margin.
        m_contacts.prepareStep(settings, m_step, m_lastMaxSpeed, m_timing);
        StepBatchRequest batch;
        batch.maxSteps = std::min({n - k, MAX_BATCH_STEPS, m_monitor.stepsBeforePoll(),
                                   m_contacts.stepsBeforeReview(m_step, settings.asyncDetection, ASYNC_POLL_STEPS)});
        batch.time = m_time;
        batch.margin = m_contacts.margin();
        // Per-contact forces are stored in a step the host can read them after: the call's last, or
        // one after which the monitor may stop the call.
        const bool polled = m_monitor.pollsAfter(batch.maxSteps);
        batch.storeContactForcesAtEnd = k + batch.maxSteps == n || polled;
        const StepBatchResult r = dynamics.steps(batch, settings, families, m_timing);
        const StepOutcome& last = r.last;
        markHostBehind();
        m_time = r.time;
        m_step += r.steps;
        k += r.steps;
        m_timing.steps += r.steps;
        collab.steps += r.steps;
        collab.batches++;
        if (r.steps < batch.maxSteps) collab.batchesEndedEarly++;
        collab.contactSetSizeSum += (double)dynamics.numContacts() * (double)r.steps;
        collab.realContactSum += (double)r.realContactSum;
        m_realContacts = last.realContacts;
        m_realSphereSphere = last.realSphereSphere;
        m_lastMaxSpeed = last.maxSpeed;
        // Travel only grows, so the last step's is the batch's largest.
        m_contacts.afterStep(last.maxTravel);
        if (last.fault || last.kernelError) reportFault(last);
        // Parked clumps (the "remove" exit policy) go at the call's end, or here once so many wait
        // that their border bin would slow detection (dynamics/OwnerStep.h, parkingPosition).
        parked = last.parkedOwners;
        if (parked >= PARKED_CLUMPS_REMOVED_AT && k < n) {
            removeParkedClumps();
            parked = 0;
            uploadIfEdited();  // the clumps are gone from the backend's state too
            dynamics.beginRun(settings, families);
        }
        if (settings.verbosity >= Verbosity::STEP_METRIC && m_timing.steps / 1000 != (m_timing.steps - r.steps) / 1000)
            log(Verbosity::STEP_METRIC,
                "t = " + std::to_string(m_time) + " s, contacts " + std::to_string(m_realContacts) + ", max speed " +
                    std::to_string(m_lastMaxSpeed) + " m/s, n_max " + std::to_string(m_contacts.nMax()));
        if (m_monitor.afterSteps(r.steps, r.steps == batch.maxSteps, m_time)) break;
    }
    m_monitor.end(m_time);
    m_state.frame.periodic.shearTime = m_time;
    if (parked) removeParkedClumps();  // a host edit: uploaded at the next call
    collab.dynamicsSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (loads) {
        clearTrackerLoads();
        dynamics.uploadTrackerLoads(m_state);
    }
}

void Simulation::syncContactDetection() {
    if (!m_initialized) return;
    m_contacts.sync(m_step, m_timing);
    markHostBehind();
}

void Simulation::refreshContactSet() {
    if (!m_initialized) return;
    uploadIfEdited();
    m_contacts.bringUpToDate(settings, m_step, m_lastMaxSpeed, m_timing);
    markHostBehind();
}

void Simulation::reportFault(const StepOutcome& r) const {
    const SimState& s = state();
    if (r.kernelError)
        throwError("DoDynamics", "simulation stopped at t = " + std::to_string(m_time) + " s: sphere " +
                                     std::to_string(sphereUserId(s, r.kernelErrorItem)) +
                                     " overlaps more triangles than the GPU's mesh contact rule can sort (" +
                                     std::to_string(MAX_MESH_CANDIDATES) + ")");
    const OwnerFault fault = faultFromFlags(r.faultFlags);
    const std::string what = fault == OwnerFault::TOO_FAST
                                 ? "moves faster than the error-out velocity (" +
                                       std::to_string(settings.errorOutVelocity) + " m/s, see SetErrorOutVelocity)"
                             : fault == OwnerFault::NOT_FINITE ? "has a non-finite velocity or orientation"
                                                               : "left the simulation domain";
    const double3 p = ownerCentre(s, r.faultOwner);
    const float3 v = s.owners.vel[r.faultOwner];
    throwError("DoDynamics", "simulation diverged at t = " + std::to_string(m_time) + " s: owner " +
                                 std::to_string(s.ownerInternalToUser[r.faultOwner]) + " " + what + "; position (" +
                                 std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
                                 "), velocity (" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " +
                                 std::to_string(v.z) + ")");
}

void Simulation::clearTrackerLoads() { m_state.trackerLoads.release(); }

void Simulation::invalidateContacts() {
    m_resume.reset();  // an edit after ReadCheckpoint: the restored set may serve no longer
    if (m_initialized) refreshKinematicCache(editState());
    m_contacts.invalidate();
}

double3 Simulation::ownerPos(size_t owner) const { return ownerCentre(state(), owner); }

void Simulation::setOwnerPos(size_t owner, const double3& p, const char* call) {
    OwnerArrays& ow = editState().owners;
    if (!encodePosition(p, m_state.frame, ow.voxel[owner], ow.subX[owner], ow.subY[owner], ow.subZ[owner]))
        throwError(call, "position (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
                             ") is outside the simulation domain");
    invalidateContacts();
}

Simulation::Resumable Simulation::resumable() const {
    stateWithContacts();  // the backend's contact set is the host's record now
    if (m_resume) return *m_resume;  // read and not yet stepped: what was read
    // Before the first step, or right after an edit, there is no set in use to go on with.
    const bool resumable = !m_backendStale && m_backends.dynamics->contactSetResumable();
    return Resumable{m_time,
                     m_step,
                     m_lastMaxSpeed,
                     m_realContacts,
                     m_realSphereSphere,
                     m_contacts.frequency().learned(),
                     m_contacts.progress(),
                     resumable};
}

void Simulation::restore(SimState&& state, const Resumable& r) {
    // The kinematics side may be reading the state being replaced: let it finish unseen first.
    m_contacts.dropOrderInFlight();
    // A checkpoint taken after grains were added holds more of them than the scene Initialize
    // built: the bin grid is sized for them as an insertion sizes it.
    const bool resized = state.owners.size() != m_state.owners.size() || state.spheres.size() != m_state.spheres.size();
    m_state = std::move(state);  // in place: the CPU backend steps this very object
    if (resized) m_grid = makeBinGrid(m_state, settings.binSize);
    m_hostStale = m_hostContactsStale = false;
    // Uploaded, contact set and all (and contacts re-detected), before the next step.
    m_backendStale = m_backendContactsStale = true;
    m_contacts.invalidate();
    m_resume = std::make_unique<Resumable>(r);
    m_time = r.time;
    m_state.frame.periodic.shearTime = m_time;  // a sheared cell's offset follows from the time
    m_step = r.step;
    m_lastMaxSpeed = r.lastMaxSpeed;
    m_realContacts = (size_t)r.realContacts;
    m_realSphereSphere = (size_t)r.realSphereSphere;
    m_contacts.restoreFrequency(r.frequency);
}

}  // namespace deme
