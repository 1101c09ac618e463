#include "runtime/ContactSetManager.h"

#include <algorithm>
#include <chrono>

#include "backend/cpu/Parallel.h"
#include "dynamics/ForcePass.h"
#include "kinematics/HistoryMapping.h"

namespace deme {

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

ContactSetManager::~ContactSetManager() = default;

void ContactSetManager::start(const SimState& s, const Settings& settings, const BinGrid& grid) {
    m_grid = grid;
    m_freq.configure(settings.updateFreq, std::max(settings.maxUpdateFreq, settings.updateFreq),
                     settings.adaptiveUpdateFreq);
    m_baseline.assign(s.owners.size(), 0.0);
    m_needDetection = true;
}

double ContactSetManager::chooseMargin(const Settings& settings, float maxSpeed) const {
    // Speed bound for the steps the set will serve: the fastest geometry now (or the user's bound),
    // plus what gravity can add meanwhile. A bound that proves too small costs an extra detection,
    // never a missed contact.
    const double n = (double)m_freq.nMax();
    const double vNow = std::max<double>(maxSpeed, settings.maxVelocity);
    const double vBound = vNow + length(settings.gravity) * n * settings.dt;
    return settings.safetyMultiplier * vBound * settings.dt * n + settings.safetyAdder;
}

void ContactSetManager::install(SimState& s, DetectedContacts& pairs, TimingStats& timing) {
    PhaseTimer t(timing, Phase::HISTORY_MAPPING);
    installDetectedContacts(s, pairs);
    buildOwnerContactIndex(s);
    m_stats.acsUpdates++;
}

void ContactSetManager::detectNow(SimState& s, const Settings& settings, const FamilyRules& families,
                                  unsigned long long step, float maxSpeed, TimingStats& timing) {
    const double t0 = now();
    if (!settings.asyncDetection && step > m_acsStep) {
        // The force pass's cost and false positives since the last detection, for n_max.
        const double steps = (double)(m_stats.steps - m_costMark.steps);
        const double force = (timing.seconds[(int)Phase::FORCE] - m_costMark.forceSeconds) / steps;
        const double pairs = m_stats.contactSetSizeSum - m_costMark.pairs;
        const double fp = pairs > 0.0 ? 1.0 - (m_stats.realContactSum - m_costMark.real) / pairs : 0.0;
        m_freq.observeSyncCost(m_costMark.detectSeconds, force, fp);
    }
    m_margin = chooseMargin(settings, maxSpeed);
    DetectedContacts pairs;
    m_detector.detect(s, m_grid, m_margin, families.contactMask(), settings.familyExtraMargin, pairs,
                      timing.seconds[(int)Phase::BINNING], timing.seconds[(int)Phase::PAIR_SEARCH]);
    install(s, pairs, timing);
    m_baseline = s.owners.travel;
    m_acsStep = step;
    m_expired = false;
    m_needDetection = false;
    m_stats.syncDetections++;
    m_costMark = CostMark{m_stats.steps, timing.seconds[(int)Phase::FORCE], m_stats.contactSetSizeSum,
                          m_stats.realContactSum, now() - t0};
}

void ContactSetManager::considerResult(SimState& s, DetectionResult& r, unsigned long long step, TimingStats& timing) {
    m_orderInFlight = false;
    m_stats.latencyStepsSum += (double)(step - r.orderStep);
    m_freq.observeLatency((unsigned int)(step - r.orderStep));
    timing.seconds[(int)Phase::BINNING] += r.binningSeconds;
    timing.seconds[(int)Phase::PAIR_SEARCH] += r.searchSeconds;
    if (r.generation != m_generation) {
        m_stats.discardedResults++;
        return;
    }
    // Usable only if nobody has moved more than its margin since the snapshot.
    const std::vector<double>& travel = s.owners.travel;
    double maxTravel = 0.0;
    for (size_t o = 0; o < travel.size(); o++) maxTravel = std::max(maxTravel, travel[o] - m_orderBaseline[o]);
    if (maxTravel > r.margin) {
        m_stats.discardedResults++;
        return;
    }
    install(s, r.pairs, timing);
    m_baseline.swap(m_orderBaseline);
    m_margin = r.margin;
    m_acsStep = r.orderStep;
    m_expired = false;
}

void ContactSetManager::prepareStep(SimState& s, const Settings& settings, const FamilyRules& families,
                                    unsigned long long step, float maxSpeed, TimingStats& timing) {
    auto due = [&] { return m_needDetection || m_expired || step - m_acsStep >= m_freq.nMax(); };
    if (!settings.asyncDetection) {
        m_worker.reset();
        m_orderInFlight = false;
        if (due()) detectNow(s, settings, families, step, maxSpeed, timing);
        return;
    }
    if (!m_worker) {
        PhaseTimer t(timing, Phase::EXCHANGE);
        m_worker.reset(new KinematicsWorker(s, m_grid, settings.kinematicsThreads));
    }
    if (m_needDetection) detectNow(s, settings, families, step, maxSpeed, timing);
    if (m_orderInFlight) {
        PhaseTimer t(timing, Phase::EXCHANGE);
        if (m_worker->tryTake(m_result)) considerResult(s, m_result, step, timing);
    }
    if (due()) {
        // The set in use may serve no longer: wait for the one in flight, or detect here.
        const double t0 = now();
        m_stats.dynamicsWaits++;
        if (m_orderInFlight) {
            m_worker->waitAndTake(m_result);
            considerResult(s, m_result, step, timing);
        }
        if (due()) detectNow(s, settings, families, step, maxSpeed, timing);
        m_stats.dynamicsWaitSeconds += now() - t0;
    }
    if (!m_orderInFlight && step - m_acsStep >= m_freq.orderAge()) {
        // kT is idle and the set in use is due for a successor: send the current state.
        PhaseTimer t(timing, Phase::EXCHANGE);
        m_orderBaseline = s.owners.travel;
        m_worker->submit(s, step, m_generation, chooseMargin(settings, maxSpeed), families.contactMask(),
                         settings.familyExtraMargin);
        m_orderInFlight = true;
        m_stats.ordersSent++;
    }
}

void ContactSetManager::sync(SimState& s, unsigned long long step, TimingStats& timing) {
    if (!m_worker || !m_orderInFlight) return;
    m_worker->waitAndTake(m_result);
    considerResult(s, m_result, step, timing);
}

void ContactSetManager::bringUpToDate(SimState& s, const Settings& settings, const FamilyRules& families,
                                      unsigned long long step, float maxSpeed, TimingStats& timing) {
    sync(s, step, timing);
    if (m_needDetection || m_expired) detectNow(s, settings, families, step, maxSpeed, timing);
}

}  // namespace deme
