// The dynamics side's decisions about contact sets (paper §2.1), apart from how detection runs (a
// CPU thread, a GPU stream, a second GPU): when the set in use may serve no longer, when to send the
// kinematics side an order, how large a margin a detection gets, whether a result that arrives may
// serve, and how n_max adapts. Plain host logic, shared by the CPU's ContactSetManager and the CUDA
// backend's DeviceSimulation so that both schedule alike, and tested without either.
//
// A contact set detected from a snapshot with margin m serves while no owner has travelled more
// than m since that snapshot, and at most n_max steps (ARCHITECTURE.md invariant 5).
#pragma once

#include <algorithm>

#include "runtime/CollaborationStats.h"
#include "runtime/Settings.h"
#include "runtime/UpdateFrequency.h"

namespace deme {

class DetectionSchedule {
  public:
    // detectionSharesDynamics: the kinematics side runs on the dynamics side's device (UpdateFrequency).
    void configure(const Settings& s, bool detectionSharesDynamics = false) {
        m_freq.configure(s.updateFreq, std::max(s.maxUpdateFreq, s.updateFreq), s.adaptiveUpdateFreq,
                         detectionSharesDynamics);
        m_asyncMark = CostMark{};
    }

    // The margin for a detection from the current state: the fastest geometry now (or the user's
    // bound), plus what gravity can add over the n_max steps the set may serve. A bound that proves
    // too small costs an extra detection (the set expires), never a missed contact; so does the cap
    // that periodic boundaries put on it (Settings::maxMargin).
    double marginFor(const Settings& s, float maxSpeed) const {
        const double n = (double)nMax();
        const double vNow = std::max<double>(maxSpeed, s.maxVelocity);
        const double vBound = vNow + length(s.gravity) * n * s.dt;
        return std::min(s.maxMargin, s.safetyMultiplier * vBound * s.dt * n + s.safetyAdder);
    }

    // Whether the set in use may not serve step `step`: a host edit, a travel beyond its margin, or
    // n_max steps since its snapshot.
    bool due(unsigned long long step) const {
        return m_needDetection || m_expired || step - m_acsStep >= nMax();
    }
    bool needsDetection() const { return m_needDetection; }
    bool expired() const { return m_expired; }
    // Asynchronous mode: with no order in flight, the set in use is old enough for its successor
    // to be ordered now (just in time: about one latency before it runs out).
    bool shouldOrder(unsigned long long step) const {
        return !m_orderInFlight && step - m_acsStep >= m_freq.orderAge();
    }
    bool orderInFlight() const { return m_orderInFlight; }
    // After the decisions before step `step` (the set in use serves it): how many steps may run, as
    // one batch (dynamics/StepBatch.h), before the schedule must look again: until the set has
    // served n_max steps; asynchronously, until an order is due, or, with one in flight,
    // `pollSteps` steps between looks for its result. A travel beyond the margin ends a batch early
    // by itself.
    unsigned long long stepsBeforeReview(unsigned long long step, bool async, unsigned int pollSteps) const {
        const unsigned long long age = step - m_acsStep, n = nMax();
        unsigned long long k = age < n ? n - age : 1;
        if (async) {
            const unsigned long long orderAt = m_freq.orderAge();
            if (m_orderInFlight)
                k = std::min<unsigned long long>(k, std::max(1u, pollSteps));
            else if (orderAt > age)
                k = std::min(k, orderAt - age);
        }
        return std::max<unsigned long long>(k, 1);
    }
    void ordered(CollaborationStats& stats) {
        m_orderInFlight = true;
        stats.ordersSent++;
    }

    // The result of the order sent at `orderStep` reached the dynamics side before step `step`.
    // Counts its latency (n_max adapts to it) and says whether it may be installed: not if a host
    // edit came after its snapshot (generation), nor if some owner has travelled more than its
    // margin since the snapshot; `maxTravelSinceOrder()` is asked only when it matters.
    template <class MaxTravel>
    bool accept(unsigned long long orderStep, unsigned long long generation, double margin, unsigned long long step,
                CollaborationStats& stats, MaxTravel&& maxTravelSinceOrder) {
        m_orderInFlight = false;
        stats.latencyStepsSum += (double)(step - orderStep);
        m_freq.observeLatency((unsigned int)(step - orderStep));
        if (generation != m_generation || maxTravelSinceOrder() > margin) {
            stats.discardedResults++;
            return false;
        }
        return true;
    }
    // Asynchronous mode, a result accepted: where detection shares the dynamics side's device, n_max
    // also balances what this detection took (`detectSeconds`, the kinematics side's time) against
    // the force pass and false positives measured since the previous accepted result.
    void afterAsyncResult(const CollaborationStats& stats, double forceSeconds, double detectSeconds) {
        if (!m_freq.detectionSharesDynamics()) return;
        double force, fp;
        if (m_asyncMark.since(stats, forceSeconds, force, fp)) m_freq.observeSharedCost(detectSeconds, force, fp);
        m_asyncMark = CostMark::at(stats, forceSeconds, 0.0);
    }
    // An order was dropped unseen (e.g. the kinematics side was drained before a host edit).
    void dropped() { m_orderInFlight = false; }

    // A set detected from the snapshot of step `snapshotStep` with `margin` now serves.
    void installed(unsigned long long snapshotStep, double margin, CollaborationStats& stats) {
        m_acsStep = snapshotStep;
        m_margin = margin;
        m_expired = m_needDetection = false;
        stats.acsUpdates++;
    }
    // After each step: the largest travel of any owner since the set's snapshot.
    void afterStep(double maxTravel) {
        if (maxTravel > m_margin) m_expired = true;
    }
    // A host-side edit of the state: detect afresh before the next step; results in flight are stale.
    void invalidate() {
        m_needDetection = true;
        m_generation++;
    }

    // Synchronous mode: before a detection on the dynamics side, n_max moves towards the balance of
    // detection cost and false positives measured since the previous one (UpdateFrequency).
    void beforeSyncDetection(bool async, unsigned long long step, const CollaborationStats& stats,
                             double forceSeconds) {
        if (async || step <= m_acsStep) return;
        double force, fp;
        if (m_costMark.since(stats, forceSeconds, force, fp)) m_freq.observeSyncCost(m_costMark.detectSeconds, force, fp);
    }
    // After it: what it cost, and the counters it is measured against next time.
    void afterSyncDetection(CollaborationStats& stats, double forceSeconds, double detectSeconds) {
        stats.syncDetections++;
        m_costMark = CostMark::at(stats, forceSeconds, detectSeconds);
    }

    // The most steps a set serves: n_max, or fewer where a sheared cell limits a set's age
    // (limitAge).
    unsigned int nMax() const { return m_freq.nMax() < m_ageLimit ? m_freq.nMax() : m_ageLimit; }
    // A sheared periodic cell: its images close in at the shear velocity, which travel does not
    // count, so a set may serve only as many steps as detection's reach allows for (0: no limit).
    void limitAge(unsigned int steps) { m_ageLimit = steps ? steps : ~0u; }
    double margin() const { return m_margin; }
    unsigned long long generation() const { return m_generation; }
    unsigned long long acsStep() const { return m_acsStep; }
    const UpdateFrequency& frequency() const { return m_freq; }
    // A restart (io/Checkpoint): n_max as the checkpointed run had adapted it.
    void restoreFrequency(const UpdateFrequency::Learned& l) { m_freq.restore(l); }
    // Where the set in use stands, for a restart that goes on with it (no detection in between), so
    // that the next detections fall on the steps they would have fallen on.
    struct Progress {
        unsigned long long acsStep = 0;
        double margin = 0.0;
        bool expired = false, needDetection = true;
    };
    Progress progress() const { return Progress{m_acsStep, m_margin, m_expired, m_needDetection}; }
    // The set in use is the restored one; an order in flight when the checkpoint was written is not.
    void resume(const Progress& p) {
        m_acsStep = p.acsStep;
        m_margin = p.margin;
        m_expired = p.expired;
        m_needDetection = p.needDetection;
        m_orderInFlight = false;
        m_generation++;
    }

  private:
    // The counters at one detection, which the cost of the steps after it is measured against.
    struct CostMark {
        unsigned long long steps = 0;
        double forceSeconds = 0.0, pairs = 0.0, real = 0.0, detectSeconds = 0.0;
        static CostMark at(const CollaborationStats& stats, double forceSeconds, double detectSeconds) {
            return CostMark{stats.steps, forceSeconds, stats.contactSetSizeSum, stats.realContactSum, detectSeconds};
        }
        // Since this mark: the force pass's seconds per step and the false-positive share of the
        // set; false if no step was taken.
        bool since(const CollaborationStats& stats, double forceNow, double& forcePerStep, double& falsePositives) const {
            const double n = (double)(stats.steps - steps);
            if (!(n > 0.0)) return false;
            forcePerStep = (forceNow - forceSeconds) / n;
            const double p = stats.contactSetSizeSum - pairs;
            falsePositives = p > 0.0 ? 1.0 - (stats.realContactSum - real) / p : 0.0;
            return true;
        }
    };
    UpdateFrequency m_freq;
    unsigned int m_ageLimit = ~0u;  // limitAge
    CostMark m_costMark, m_asyncMark;
    double m_margin = 0.0;
    unsigned long long m_acsStep = 0, m_generation = 0;
    bool m_orderInFlight = false, m_expired = false, m_needDetection = true;
};

}  // namespace deme
