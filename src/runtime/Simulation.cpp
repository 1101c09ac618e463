#include "runtime/Simulation.h"

#include <algorithm>
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

namespace deme {

void Simulation::log(Verbosity level, const std::string& msg) const {
    if (settings.verbosity < level) return;
    std::ostream& os = level <= Verbosity::WARNING ? std::cerr : std::cout;
    os << (level == Verbosity::ERROR     ? "[deme] error: "
           : level == Verbosity::WARNING ? "[deme] warning: "
                                         : "[deme] ")
       << msg << std::endl;
}

void Simulation::start(SimState&& state) {
    m_state = std::move(state);
    refreshKinematicCache(m_state);
    m_grid = makeBinGrid(m_state, settings.binSize);
    m_initialized = true;
    m_needDetection = true;
    log(Verbosity::INFO, "initialized: " + std::to_string(m_state.numClumps) + " clumps, " +
                             std::to_string(m_state.spheres.size()) + " spheres, " +
                             std::to_string(m_state.analytical.size()) + " analytical components; bin size " +
                             std::to_string(m_grid.size) + " (" + std::to_string(m_grid.numBins()) + " bins), " +
                             std::to_string(cpuThreadCount()) + " CPU threads");
}

double Simulation::chooseMargin() const {
    // Speed bound for the coming n steps: the fastest geometry now (or the user's bound), plus what
    // gravity can add meanwhile.
    const double n = (double)std::max(1u, settings.updateFreq);
    const double vNow = std::max<double>(m_lastMaxSpeed, settings.maxVelocity);
    const double g = length(settings.gravity);
    const double vBound = vNow + g * n * settings.dt;
    return settings.safetyMultiplier * vBound * settings.dt * n + settings.safetyAdder;
}

void Simulation::detectContacts() {
    m_margin = chooseMargin();
    DetectedContacts fresh;
    {
        PhaseTimer t(m_timing, Phase::DETECTION);
        m_detector.detect(m_state, m_grid, m_margin, families.contactMask(), fresh);
    }
    {
        PhaseTimer t(m_timing, Phase::HISTORY_MAPPING);
        installDetectedContacts(m_state, fresh);
        buildOwnerContactIndex(m_state);
    }
    std::fill(m_state.owners.travel.begin(), m_state.owners.travel.end(), 0.f);
    m_timing.detections++;
    m_timing.contactsPerDetection += (double)m_state.contacts.size();
    m_stepsSinceDetection = 0;
    m_needDetection = false;
}

void Simulation::advance(unsigned long long n) {
    for (unsigned long long k = 0; k < n; k++) {
        if (m_needDetection || m_stepsSinceDetection >= settings.updateFreq) detectContacts();
        {
            PhaseTimer t(m_timing, Phase::FORCE);
            resolveMeshContacts(m_state);
            const ForcePassResult r = computeContactForces(m_state, m_time, settings.dt);
            m_realContacts = r.realContacts;
            m_realSphereSphere = r.realSphereSphere;
        }
        IntegrationResult ir;
        {
            PhaseTimer t(m_timing, Phase::INTEGRATION);
            families.evaluate(m_time + settings.dt, m_stepMotion);
            ir = integrateOwners(m_state, m_stepMotion, settings.gravity, settings.dt, settings.errorOutVelocity);
        }
        m_time += settings.dt;
        m_timing.steps++;
        m_stepsSinceDetection++;
        m_lastMaxSpeed = ir.maxSurfaceSpeed;
        if (ir.fault != OwnerFault::NONE) {
            const std::string what = ir.fault == OwnerFault::TOO_FAST ? "moves faster than the error-out velocity (" +
                                                                            std::to_string(settings.errorOutVelocity) +
                                                                            " m/s, see SetErrorOutVelocity)"
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
        // The margin is used up: detect before the next step rather than risk a missed contact.
        if (ir.maxTravel > m_margin) {
            m_needDetection = true;
            m_timing.earlyDetections++;
        }
        if (settings.verbosity >= Verbosity::STEP_METRIC && m_timing.steps % 1000 == 0)
            log(Verbosity::STEP_METRIC, "t = " + std::to_string(m_time) + " s, contacts " +
                                            std::to_string(m_realContacts) + ", max speed " +
                                            std::to_string(m_lastMaxSpeed) + " m/s");
    }
    clearTrackerLoads();
}

void Simulation::clearTrackerLoads() {
    std::fill(m_state.owners.extraAcc.begin(), m_state.owners.extraAcc.end(), make_float3(0.f));
    std::fill(m_state.owners.extraAngAcc.begin(), m_state.owners.extraAngAcc.end(), make_float3(0.f));
}

void Simulation::invalidateContacts() {
    if (m_initialized) refreshKinematicCache(m_state);
    m_needDetection = true;
}

double3 Simulation::ownerPos(size_t owner) const { return ownerPosition(m_state, (bodyID_t)owner); }

void Simulation::setOwnerPos(size_t owner, const double3& p, const char* call) {
    OwnerArrays& ow = m_state.owners;
    if (!encodePosition(p, m_state.frame, ow.voxel[owner], ow.subX[owner], ow.subY[owner], ow.subZ[owner]))
        throwError(call, "position (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
                             ") is outside the simulation domain");
    invalidateContacts();
}

}  // namespace deme
