#include "backend/cuda/CudaDynamics.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include <cuda_runtime_api.h>

#include "backend/cuda/CudaCheck.h"
#include "backend/cuda/Device.h"
#include "dynamics/OwnerStep.h"

namespace deme::cuda {

namespace {

constexpr unsigned int THREADS = 256;
constexpr const char* CALL = "DoDynamics";

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

void CudaDynamics::refreshView() {
    m_state.viewInto(m_view);
    viewContacts(m_contacts[m_current], m_numContacts, m_view);
}

void CudaDynamics::upload(const SimState& s) {
    select();
    const Stream st = m_stream;
    m_state.upload(s, st);
    m_baseline.resizeDiscarding(s.owners.size());
    if (!s.owners.travel.empty()) m_baseline.uploadAsync(s.owners.travel.data(), s.owners.size(), st);
    m_orderBaseline.resizeDiscarding(s.owners.size());
    // The contact set the host has (history included).
    m_W = s.numWildcards;
    m_current = 0;
    m_numContacts = (uint32_t)s.contacts.size();
    uploadContacts(s.contacts, m_W, m_contacts[0], st);
    m_motion.resizeDiscarding(NUM_FAMILIES);
    m_reduction.resizeDiscarding(1);
    m_maxTravelBits.resizeDiscarding(1);
    synchronize(st);
    // The model's tables and wildcards and the persistence rules (copied on the legacy stream and
    // waited for, so dT's stream finds them in place).
    m_model.upload(s);
    m_history.uploadRules(s.wildcards.contactInit);
    synchronize(nullptr);

    m_view.frame = s.frame;
    m_view.domainSize = s.domainSize;
    m_view.numWildcards = s.numWildcards;
    m_view.numOwners = (uint32_t)s.owners.size();
    m_view.numSpheres = (uint32_t)s.spheres.size();
    m_view.numAnalytical = (uint32_t)s.analytical.size();
    m_view.numTriangles = (uint32_t)s.triangles.size();
    m_numClumps = (uint32_t)s.numClumps;
    m_numAnalyticalOwners = (uint32_t)s.numAnalyticalOwners;
    m_domainDiagonal = length(s.domainSize);
    refreshView();
    m_subsetStale = true;
}

void CudaDynamics::download(SimState& s) {
    select();
    m_state.download(s, m_stream);
    downloadContacts(m_contacts[m_current], m_numContacts, m_W, s.contacts, m_stream);
    synchronize(m_stream);
    m_model.download(s);
}

void CudaDynamics::uploadTrackerLoads(const SimState& s) {
    select();
    m_state.owners.extraAcc.uploadAsync(s.owners.extraAcc.data(), s.owners.extraAcc.size(), m_stream);
    m_state.owners.extraAngAcc.uploadAsync(s.owners.extraAngAcc.data(), s.owners.extraAngAcc.size(), m_stream);
    // The host vectors may change before the next step reads them.
    synchronize(m_stream);
}

void CudaDynamics::downloadStepFlags(std::vector<uint8_t>& flags) {
    select();
    const DeviceBuffer<uint8_t>& d = m_state.integrationScratch.flags;
    flags.resize(d.size());
    if (!flags.empty()) d.downloadAsync(flags.data(), flags.size(), m_stream);
    synchronize(m_stream);
}

void CudaDynamics::beginRun(const Settings&, const FamilyRules& families) {
    // dT's GPU stays current for the call's steps (and the contact-set work between them).
    select();
    prepareFamilyMotion(families);
    m_subsetStale = true;
}

StepOutcome CudaDynamics::step(double time, const Settings& settings, const FamilyRules&, bool storeContactForces,
                               TimingStats& timing) {
    const Stream st = m_stream;
    const unsigned int nO = m_view.numOwners, nS = m_view.numSpheres, nT = m_view.numTriangles;
    const StepConstants consts{settings.gravity, (float)settings.dt,
                               settings.dt,      settings.errorOutVelocity * settings.errorOutVelocity,
                               m_view.frame,     m_view.domainSize};
    if (m_steps++ == m_profileFromStep) startProfilerCapture();
    const double t0 = now();
    DEME_CUDA_CHECK(CALL, cudaEventRecord(static_cast<cudaEvent_t>(m_forceStart), static_cast<cudaStream_t>(st)));
    launch(kFamilyMotion, 1, NUM_FAMILIES, 0, st, time + settings.dt, m_motion.data());
    if (m_subsetStale) updateStepSubset();  // after a detection: O(owners), reads this step's motion
    const bodyID_t* ownerIds = m_subsetAll ? nullptr : m_steppedOwners.data();
    const bodyID_t* sphereIds = m_subsetAll ? nullptr : m_steppedSpheres.data();
    const unsigned int nStepped = m_subsetAll ? nO : m_numSteppedOwners;
    const unsigned int nPlaced = m_subsetAll ? nS : m_numSteppedSpheres;
    StepReduction* red = m_reduction.data();
    launch(kResetReduction, 1, 32, 0, st, red);
    if (nT && m_numContacts) launch(kResolveMesh, blocksFor(m_numContacts, THREADS), THREADS, 0, st, m_view, red);
    launch(kClearLoads, blocksFor(nO, THREADS), THREADS, 0, st, m_view);
    StateView stepView = m_view;
    if (!storeContactForces) stepView.contacts.force = nullptr;
    m_model.launch(stepView, (float)time, (float)settings.dt, m_numClumps, nO - m_numClumps, red, st,
                   settings.threadsPerBlock);
    DEME_CUDA_CHECK(CALL, cudaEventRecord(static_cast<cudaEvent_t>(m_forceEnd), static_cast<cudaStream_t>(st)));
    // Contact forces were summed onto every owner (dormant ones too: trackers read them); only the
    // stepped owners are integrated and placed.
    if (nStepped)
        launch(kIntegrate, blocksFor(nStepped, THREADS), THREADS, 0, st, m_view,
               (const FamilyStepMotion*)m_motion.data(), consts, (const double*)m_baseline.data(), ownerIds, nStepped,
               red);
    if (nStepped)
        launch(kLargeRot, blocksFor(nStepped, THREADS), THREADS, 0, st, m_view, ownerIds, nStepped, (float)settings.dt);
    if (nPlaced) launch(kPlaceSpheres, blocksFor(nPlaced, THREADS), THREADS, 0, st, m_view, sphereIds, nPlaced);
    if (nT) launch(kPlaceTris, blocksFor(nT, THREADS), THREADS, 0, st, m_view);
    if (m_numAnalyticalOwners)
        launch(kAnalytical, blocksFor(m_numAnalyticalOwners, THREADS), THREADS, 0, st, m_view, m_numClumps,
               m_numAnalyticalOwners, (float)settings.dt, m_domainDiagonal, (const double*)m_baseline.data(), red);
    StepReduction r;
    m_reduction.downloadAsync(&r, 1, st);
    synchronize(st);
    float forceMs = 0.f;
    DEME_CUDA_CHECK(CALL, cudaEventElapsedTime(&forceMs, static_cast<cudaEvent_t>(m_forceStart),
                                               static_cast<cudaEvent_t>(m_forceEnd)));
    const double stepSeconds = now() - t0, forceSeconds = std::min(stepSeconds, 1e-3 * (double)forceMs);
    timing.seconds[(int)Phase::FORCE] += forceSeconds;
    timing.seconds[(int)Phase::INTEGRATION] += stepSeconds - forceSeconds;

    StepOutcome out;
    out.realContacts = r.realContacts;
    out.realSphereSphere = r.realSphereSphere;
    std::memcpy(&out.maxSpeed, &r.maxSpeedBits, sizeof(float));
    std::memcpy(&out.maxTravel, &r.maxTravelBits, sizeof(double));
    out.kernelError = r.errorFlags;
    out.kernelErrorItem = r.errorItem;
    if (r.firstFault != 0xFFFFFFFFu) {
        out.fault = true;
        out.faultOwner = r.firstFault;
        m_state.integrationScratch.flags.downloadAsync(&out.faultFlags, 1, st, r.firstFault);
        synchronize(st);
    }
    return out;
}

std::string CudaDynamics::description() const { return "GPU " + std::to_string(m_device) + " (" + m_name + ")"; }

}  // namespace deme::cuda
