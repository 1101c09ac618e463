#include "runtime/Simulation.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <iostream>

#include <deme/Error.h>

#include "backend/cpu/Parallel.h"
#include "dynamics/ContactInputsGather.h"
#include "dynamics/ForcePass.h"
#include "dynamics/Integration.h"
#include "dynamics/KinematicCache.h"
#include "dynamics/MeshContacts.h"
#include "kinematics/HistoryMapping.h"
#include "runtime/BackendSelection.h"
#ifdef DEME_HAS_CUDA
#include "backend/cuda/DeviceSimulation.h"
#include "backend/cuda/kernels/KernelArgs.cuh"
#else
namespace deme::cuda {
class DeviceSimulation {};  // never created in a build without the CUDA backend
}  // namespace deme::cuda
#endif

namespace deme {

void Simulation::log(Verbosity level, const std::string& msg) const {
    if (settings.verbosity < level) return;
    std::ostream& os = level <= Verbosity::WARNING ? std::cerr : std::cout;
    os << (level == Verbosity::ERROR     ? "[deme] error: "
           : level == Verbosity::WARNING ? "[deme] warning: "
                                         : "[deme] ")
       << msg << std::endl;
}

Simulation::Simulation() = default;
Simulation::~Simulation() = default;

void Simulation::start(SimState&& state, ActiveForceModel&& model) {
    m_state = std::move(state);
    m_model = std::move(model);
    refreshKinematicCache(m_state);
    m_grid = makeBinGrid(m_state, settings.binSize);
    applyDetectionMode();
    m_contacts.start(m_state, settings, m_grid);
    startDevice();
    m_initialized = true;
    log(Verbosity::INFO, "initialized: " + std::to_string(m_state.numClumps) + " clumps, " +
                             std::to_string(m_state.spheres.size()) + " spheres, " +
                             std::to_string(m_state.analytical.size()) + " analytical components; bin size " +
                             std::to_string(m_grid.size) + " (" + std::to_string(m_grid.numBins()) + " bins), " +
                             std::to_string(cpuThreadCount()) + " CPU threads for dynamics, contact detection " +
                             (settings.asyncDetection ? "on its own thread" : "on the dynamics thread"));
    const std::string how = m_model.layout.builtIn() ? "built in"
                            : m_model.cacheHit       ? "compiled earlier, loaded from the cache"
                                                     : "compiled in " + std::to_string(m_model.compileSeconds) + " s";
    log(Verbosity::INFO, "force model: " + m_model.layout.description() + " (" + how + ")");
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

void Simulation::startDevice() {
    const BackendRequest request = settings.backend.empty() ? backendRequestFromEnvironment()
                                                            : parseBackendRequest("Initialize", settings.backend);
    const BackendChoice choice =
        resolveBackend("Initialize", request, [this](Verbosity v, const std::string& msg) { log(v, msg); });
    settings.onGpu = choice.kind == BackendKind::Cuda;
    if (!settings.onGpu) return;
    // Every force model runs on the GPU: built-in ones are kernels of the library, a custom one is
    // compiled for the GPU here too (NVRTC, cached), beside its CPU build.
#ifdef DEME_HAS_CUDA
    // One GPU: dynamics and kinematics share it, each on its own stream. Two (or more; the first two
    // are used): dynamics on the first, kinematics on the second, as in the paper.
    const std::vector<int>& ids = settings.deviceIds;
    const int device = ids.empty() ? choice.deviceId : ids[0];
    const int kinematicsDevice = ids.size() > 1 ? ids[1] : device;
    if (ids.size() > 2)
        log(Verbosity::WARNING, std::to_string(ids.size()) + " GPUs were given; the CUDA backend uses two (GPU " +
                                    std::to_string(device) + " for dynamics, GPU " +
                                    std::to_string(kinematicsDevice) + " for contact detection)");
    const auto t0 = std::chrono::steady_clock::now();
    m_device.reset(new cuda::DeviceSimulation(device, kinematicsDevice, settings, m_model.layout));
    log(Verbosity::INFO, "GPU kernels for " + m_device->deviceName() +
                             (kinematicsDevice != device ? " and " + m_device->kinematicsDeviceName() : std::string()) +
                             (m_device->kernelsFromCache() ? " loaded from the cache" : " compiled") + " in " +
                             std::to_string(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()) +
                             " s; contact detection on GPU " + std::to_string(kinematicsDevice) +
                             (kinematicsDevice == device ? " (its own stream)"
                              : m_device->kinematicsPeerAccess() ? " (peer access to GPU " + std::to_string(device) + ")"
                                                                  : " (no peer access: transfers through the host)") +
                             (settings.asyncDetection ? ", asynchronous" : ", synchronous"));
    m_deviceStale = true;
#endif
}

const SimState& Simulation::state() const {
#ifdef DEME_HAS_CUDA
    if (m_hostStale && m_device) {
        m_device->download(m_state);
        m_hostStale = false;
    }
#endif
    return m_state;
}

SimState& Simulation::editState() {
    state();
    m_deviceStale = true;
    return m_state;
}

void Simulation::advanceOnDevice(unsigned long long n) {
#ifdef DEME_HAS_CUDA
    CollaborationStats& collab = m_contacts.stats();
    const auto t0 = std::chrono::steady_clock::now();
    if (m_deviceStale) {
        m_device->upload(m_state, m_grid, settings, families, collab);
        m_deviceStale = false;
    }
    const bool loads = m_state.hasTrackerLoads;
    if (loads) m_device->uploadTrackerLoads(m_state);
    cuda::DeviceStepTotals totals;
    const cuda::DeviceFault fault =
        m_device->advance(n, settings, families, m_time, m_step, m_timing, collab, totals, m_monitor);
    m_hostStale = true;
    m_realContacts = totals.realContacts;
    m_realSphereSphere = totals.realSphereSphere;
    m_lastMaxSpeed = totals.maxSpeed;
    collab.dynamicsSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (loads) {
        clearTrackerLoads();
        m_device->uploadTrackerLoads(m_state);
    }
    if (fault.kernelError) {
        state();
        throwError("DoDynamics", "simulation stopped at t = " + std::to_string(m_time) + " s: sphere " +
                                     std::to_string(m_state.sphereInternalToUser[fault.kernelErrorItem]) +
                                     " overlaps more triangles than the GPU's mesh contact rule can sort (" +
                                     std::to_string(MAX_MESH_CANDIDATES) + ")");
    }
    if (fault.any) {
        state();
        IntegrationResult ir;
        ir.fault = faultFromFlags(fault.flags);
        ir.faultOwner = fault.owner;
        reportFault(ir);
    }
#else
    (void)n;
#endif
}

void Simulation::advance(unsigned long long n) {
    m_monitor.begin(n, m_time, settings.dt, m_state.spheres.size());
    if (m_device) {
        advanceOnDevice(n);
        m_monitor.end(m_time);
        return;
    }
    CollaborationStats& collab = m_contacts.stats();
    const auto t0 = std::chrono::steady_clock::now();
    for (unsigned long long k = 0; k < n; k++) {
        m_monitor.pollsAfterThisStep();
        m_contacts.prepareStep(m_state, settings, families, m_step, m_lastMaxSpeed, m_timing);
        {
            PhaseTimer t(m_timing, Phase::FORCE);
            resolveMeshContacts(m_state);
            const ForcePassResult r = m_model.pass(m_state, m_time, settings.dt);
            m_realContacts = r.realContacts;
            m_realSphereSphere = r.realSphereSphere;
        }
        {
            PhaseTimer t(m_timing, Phase::REDUCTION);
            reduceContactForces(m_state);
        }
        IntegrationResult ir;
        {
            PhaseTimer t(m_timing, Phase::INTEGRATION);
            families.evaluate(m_time + settings.dt, m_stepMotion);
            ir = integrateOwners(m_state, m_stepMotion, settings.gravity, settings.dt, settings.errorOutVelocity,
                                 m_contacts.travelBaseline());
        }
        m_time += settings.dt;
        m_step++;
        m_timing.steps++;
        collab.steps++;
        collab.contactSetSizeSum += (double)m_state.contacts.size();
        collab.realContactSum += (double)m_realContacts;
        m_lastMaxSpeed = ir.maxSurfaceSpeed;
        if (ir.fault != OwnerFault::NONE) reportFault(ir);
        m_contacts.afterStep(ir.maxTravel);
        if (settings.verbosity >= Verbosity::STEP_METRIC && m_timing.steps % 1000 == 0)
            log(Verbosity::STEP_METRIC,
                "t = " + std::to_string(m_time) + " s, contacts " + std::to_string(m_realContacts) + ", max speed " +
                    std::to_string(m_lastMaxSpeed) + " m/s, n_max " + std::to_string(m_contacts.nMax()));
        if (m_monitor.afterStep(m_time)) break;
    }
    m_monitor.end(m_time);
    collab.dynamicsSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    clearTrackerLoads();
}

void Simulation::syncContactDetection() {
#ifdef DEME_HAS_CUDA
    if (m_device) {
        if (!m_deviceStale) m_device->finishDetection(m_step, m_timing, m_contacts.stats());
        return;
    }
#endif
    if (m_initialized) m_contacts.sync(m_state, m_step, m_timing);
}

void Simulation::refreshContactSet() {
    if (m_initialized) m_contacts.bringUpToDate(m_state, settings, families, m_step, m_lastMaxSpeed, m_timing);
}

void Simulation::reportFault(const IntegrationResult& ir) const {
    const std::string what = ir.fault == OwnerFault::TOO_FAST
                                 ? "moves faster than the error-out velocity (" +
                                       std::to_string(settings.errorOutVelocity) + " m/s, see SetErrorOutVelocity)"
                             : ir.fault == OwnerFault::NOT_FINITE ? "has a non-finite velocity or orientation"
                                                                  : "left the simulation domain";
    const double3 p = ownerPosition(m_state, (bodyID_t)ir.faultOwner);
    const float3 v = m_state.owners.vel[ir.faultOwner];
    throwError("DoDynamics", "simulation diverged at t = " + std::to_string(m_time) + " s: owner " +
                                 std::to_string(m_state.ownerInternalToUser[ir.faultOwner]) + " " + what +
                                 "; position (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " +
                                 std::to_string(p.z) + "), velocity (" + std::to_string(v.x) + ", " +
                                 std::to_string(v.y) + ", " + std::to_string(v.z) + ")");
}

void Simulation::clearTrackerLoads() {
    if (!m_state.hasTrackerLoads) return;
    std::fill(m_state.owners.extraAcc.begin(), m_state.owners.extraAcc.end(), make_float3(0.f));
    std::fill(m_state.owners.extraAngAcc.begin(), m_state.owners.extraAngAcc.end(), make_float3(0.f));
    m_state.hasTrackerLoads = false;
}

void Simulation::invalidateContacts() {
    if (m_initialized) refreshKinematicCache(editState());
    m_contacts.invalidate();
}

double Simulation::currentMargin() const {
#ifdef DEME_HAS_CUDA
    if (m_device) return m_device->margin();
#endif
    return m_contacts.margin();
}

unsigned int Simulation::updateFreq() const {
#ifdef DEME_HAS_CUDA
    if (m_device) return m_device->nMax();
#endif
    return m_contacts.nMax();
}

double3 Simulation::ownerPos(size_t owner) const { return ownerPosition(state(), (bodyID_t)owner); }

void Simulation::setOwnerPos(size_t owner, const double3& p, const char* call) {
    OwnerArrays& ow = editState().owners;
    if (!encodePosition(p, m_state.frame, ow.voxel[owner], ow.subX[owner], ow.subY[owner], ow.subZ[owner]))
        throwError(call, "position (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
                             ") is outside the simulation domain");
    invalidateContacts();
}

}  // namespace deme
