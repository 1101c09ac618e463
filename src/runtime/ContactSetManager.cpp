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
    m_schedule.configure(settings);
    m_baseline.assign(s.owners.size(), 0.0);
    m_schedule.invalidate();
}

void ContactSetManager::install(SimState& s, DetectedContacts& pairs, unsigned long long snapshotStep, double margin,
                                TimingStats& timing) {
    PhaseTimer t(timing, Phase::HISTORY_MAPPING);
    installDetectedContacts(s, pairs);
    buildOwnerContactIndex(s);
    m_schedule.installed(snapshotStep, margin, m_stats);
}

void ContactSetManager::detectNow(SimState& s, const Settings& settings, const FamilyRules& families,
                                  unsigned long long step, float maxSpeed, TimingStats& timing) {
    const double t0 = now();
    m_schedule.beforeSyncDetection(settings.asyncDetection, step, m_stats, timing.seconds[(int)Phase::FORCE]);
    const double margin = m_schedule.marginFor(settings, maxSpeed);
    DetectedContacts pairs;
    m_detector.detect(s, m_grid, margin, families.contactMask(), settings.familyExtraMargin, pairs,
                      timing.seconds[(int)Phase::BINNING], timing.seconds[(int)Phase::PAIR_SEARCH]);
    install(s, pairs, step, margin, timing);
    m_baseline = s.owners.travel;
    m_schedule.afterSyncDetection(m_stats, timing.seconds[(int)Phase::FORCE], now() - t0);
}

void ContactSetManager::considerResult(SimState& s, DetectionResult& r, unsigned long long step, TimingStats& timing) {
    timing.seconds[(int)Phase::BINNING] += r.binningSeconds;
    timing.seconds[(int)Phase::PAIR_SEARCH] += r.searchSeconds;
    // Usable only if nobody has moved more than its margin since the snapshot.
    auto maxTravel = [&] {
        const std::vector<double>& travel = s.owners.travel;
        double m = 0.0;
        for (size_t o = 0; o < travel.size(); o++) m = std::max(m, travel[o] - m_orderBaseline[o]);
        return m;
    };
    if (!m_schedule.accept(r.orderStep, r.generation, r.margin, step, m_stats, maxTravel)) return;
    install(s, r.pairs, r.orderStep, r.margin, timing);
    m_baseline.swap(m_orderBaseline);
}

void ContactSetManager::prepareStep(SimState& s, const Settings& settings, const FamilyRules& families,
                                    unsigned long long step, float maxSpeed, TimingStats& timing) {
    if (!settings.asyncDetection) {
        if (m_worker) {
            m_worker.reset();
            m_schedule.dropped();
        }
        if (m_schedule.due(step)) detectNow(s, settings, families, step, maxSpeed, timing);
        return;
    }
    if (!m_worker) {
        PhaseTimer t(timing, Phase::EXCHANGE);
        m_worker.reset(new KinematicsWorker(s, m_grid, settings.kinematicsThreads));
    }
    if (m_schedule.needsDetection()) detectNow(s, settings, families, step, maxSpeed, timing);
    if (m_schedule.orderInFlight()) {
        PhaseTimer t(timing, Phase::EXCHANGE);
        if (m_worker->tryTake(m_result)) considerResult(s, m_result, step, timing);
    }
    if (m_schedule.due(step)) {
        // The set in use may serve no longer: wait for the one in flight, or detect here.
        const double t0 = now();
        m_stats.dynamicsWaits++;
        if (m_schedule.orderInFlight()) {
            m_worker->waitAndTake(m_result);
            considerResult(s, m_result, step, timing);
        }
        if (m_schedule.due(step)) detectNow(s, settings, families, step, maxSpeed, timing);
        m_stats.dynamicsWaitSeconds += now() - t0;
    }
    if (m_schedule.shouldOrder(step)) {
        // kT is idle and the set in use is due for a successor: send the current state.
        PhaseTimer t(timing, Phase::EXCHANGE);
        m_orderBaseline = s.owners.travel;
        m_worker->submit(s, step, m_schedule.generation(), m_schedule.marginFor(settings, maxSpeed),
                         families.contactMask(), settings.familyExtraMargin);
        m_schedule.ordered(m_stats);
    }
}

void ContactSetManager::sync(SimState& s, unsigned long long step, TimingStats& timing) {
    if (!m_worker || !m_schedule.orderInFlight()) return;
    m_worker->waitAndTake(m_result);
    considerResult(s, m_result, step, timing);
}

void ContactSetManager::bringUpToDate(SimState& s, const Settings& settings, const FamilyRules& families,
                                      unsigned long long step, float maxSpeed, TimingStats& timing) {
    sync(s, step, timing);
    if (m_schedule.needsDetection() || m_schedule.expired()) detectNow(s, settings, families, step, maxSpeed, timing);
}

}  // namespace deme
