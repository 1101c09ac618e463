#include "runtime/ContactSetManager.h"

#include <deme/Error.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace deme {

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

void ContactSetManager::start(const Settings& settings, DynamicsBackend& dynamics, KinematicsBackend& kinematics) {
    m_dynamics = &dynamics;
    m_kinematics = &kinematics;
    // n_max is configured once; later starts (after host-side edits) keep what it adapted to.
    if (!m_configured) m_schedule.configure(settings, kinematics.sharesDynamicsDevice());
    m_configured = true;
    m_schedule.invalidate();
}

DetectionOrder ContactSetManager::orderFor(const Settings& settings, unsigned long long step, float maxSpeed) const {
    DetectionOrder o{step, m_schedule.generation(), m_schedule.marginFor(settings, maxSpeed)};
    if (period && period->shear) {
        // Images across the z faces close in at up to the shear velocity, which no owner's travel
        // counts: detection reaches that much further, within the periodic cap.
        o.shearTime = period->shearTime;
        o.imageDrift = std::fabs(period->shearVelocity) * (double)m_schedule.nMax() * settings.dt;
        if (o.imageDrift >= settings.maxMargin)
            throwError("DoDynamics", "the sheared cell's images move " + std::to_string(o.imageDrift) +
                                         " m in n_max = " + std::to_string(m_schedule.nMax()) +
                                         " steps, more than the periods allow detection to reach (" +
                                         std::to_string(settings.maxMargin) +
                                         " m): lower the shear rate, the time step or SetCDMaxUpdateFreq");
        o.margin = std::min(o.margin, settings.maxMargin - 0.5 * o.imageDrift);
    }
    return o;
}

// Every detection's time counts, installed or not.
void ContactSetManager::account(const DetectionReport& r, TimingStats& timing) {
    timing.seconds[(int)Phase::BINNING] += r.binningSeconds;
    timing.seconds[(int)Phase::PAIR_SEARCH] += r.searchSeconds;
}

void ContactSetManager::install(const DetectionReport& r, TimingStats& timing) {
    if (beforeInstall) beforeInstall(r.numPairs);  // may throw: then nothing has changed
    m_dynamics->install(r, timing);
    m_schedule.installed(r.order.step, r.order.margin, m_stats);
}

// Detection from the current state, waited for (synchronous mode, the first step, after edits):
// valid by construction.
void ContactSetManager::detectNow(const Settings& settings, unsigned long long step, float maxSpeed,
                                  TimingStats& timing) {
    sync(step, timing);  // the kinematics side takes one order at a time
    limitShearedAge(settings);
    const double t0 = now();
    m_schedule.beforeSyncDetection(settings.asyncDetection, step, m_stats, timing.seconds[(int)Phase::FORCE]);
    if (beforeDetection) beforeDetection();
    const bool setServesNoStep = m_dynamics->beforeDetectNow();
    m_dynamics->markOrderBaseline(true);
    try {
        DetectionReport r;
        m_kinematics->detectNow(orderFor(settings, step, maxSpeed), r);
        account(r, timing);
        install(r, timing);
    } catch (...) {
        if (setServesNoStep) m_schedule.invalidate();  // detect afresh before any step
        throw;
    }
    m_schedule.afterSyncDetection(m_stats, timing.seconds[(int)Phase::FORCE], now() - t0);
}

// A result arrived: installed if it may serve (DetectionSchedule::accept).
void ContactSetManager::consider(const DetectionReport& r, unsigned long long step, TimingStats& timing) {
    account(r, timing);
    if (!m_schedule.accept(r.order.step, r.order.generation, r.order.margin, step, m_stats,
                           [this] { return m_dynamics->maxTravelSinceOrder(); }))
        return;
    install(r, timing);
    m_schedule.afterAsyncResult(m_stats, timing.seconds[(int)Phase::FORCE], r.binningSeconds + r.searchSeconds);
}

// A sheared cell: a set serves at most as many steps as keep the images' drift within half of what
// the periods let detection reach (orderFor).
void ContactSetManager::limitShearedAge(const Settings& settings) {
    if (!period || !period->shear) return;
    const double perStep = std::fabs(period->shearVelocity) * settings.dt;
    const double steps = perStep > 0.0 ? std::floor(0.5 * settings.maxMargin / perStep) : 0.0;
    m_schedule.limitAge(perStep > 0.0 ? (unsigned int)std::max(1.0, std::min(steps, 1e9)) : 0u);
}

void ContactSetManager::prepareStep(const Settings& settings, unsigned long long step, float maxSpeed,
                                    TimingStats& timing) {
    limitShearedAge(settings);
    if (!settings.asyncDetection) {
        sync(step, timing);  // left from an asynchronous call before a switch
        if (m_schedule.due(step)) detectNow(settings, step, maxSpeed, timing);
        return;
    }
    if (m_schedule.needsDetection()) detectNow(settings, step, maxSpeed, timing);
    if (m_schedule.orderInFlight()) {
        PhaseTimer t(timing, Phase::EXCHANGE);
        DetectionReport r;
        if (m_kinematics->tryTake(r)) consider(r, step, timing);
    }
    if (m_schedule.due(step)) {
        // The set in use may serve no longer: wait for the one in flight, or detect here.
        const double t0 = now();
        m_stats.dynamicsWaits++;
        sync(step, timing);
        if (m_schedule.due(step)) detectNow(settings, step, maxSpeed, timing);
        m_stats.dynamicsWaitSeconds += now() - t0;
    }
    if (m_schedule.shouldOrder(step)) {
        // The kinematics side is idle and the set in use is due for a successor: send the state now.
        PhaseTimer t(timing, Phase::EXCHANGE);
        if (beforeDetection) beforeDetection();
        m_dynamics->markOrderBaseline(false);
        m_kinematics->submit(orderFor(settings, step, maxSpeed));
        m_schedule.ordered(m_stats);
    }
}

void ContactSetManager::sync(unsigned long long step, TimingStats& timing) {
    if (!m_schedule.orderInFlight()) return;
    DetectionReport r;
    m_kinematics->waitAndTake(r);
    consider(r, step, timing);
}

void ContactSetManager::bringUpToDate(const Settings& settings, unsigned long long step, float maxSpeed,
                                      TimingStats& timing) {
    sync(step, timing);
    if (m_schedule.needsDetection() || m_schedule.expired()) detectNow(settings, step, maxSpeed, timing);
}

void ContactSetManager::dropOrderInFlight() {
    if (!m_schedule.orderInFlight()) return;
    DetectionReport r;
    m_kinematics->waitAndTake(r);
    m_schedule.dropped();
    m_stats.discardedResults++;
}

}  // namespace deme
