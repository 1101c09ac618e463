// Keeps the dynamics side supplied with a valid active-contact set (ACS), detected synchronously or
// asynchronously by the kinematics side (paper §2.1), on either backend: the one place that decides
// when to detect, wait or swap contact sets. The decisions themselves (due, order, accept, n_max)
// are runtime/DetectionSchedule.h's; the work is the backends' (runtime/Backends.h).
//
// Validity: an ACS detected from a snapshot with margin m stays valid while no owner has travelled
// more than m since that snapshot (see kinematics/DetectionRules.h for the no-miss bound). The
// steps report the largest travel every step; the manager never lets a step run on an expired set:
// it waits for the set in flight or detects on the spot.
#pragma once

#include <functional>

#include "physics/Periodic.h"
#include "runtime/Backends.h"
#include "runtime/CollaborationStats.h"
#include "runtime/DetectionSchedule.h"

namespace deme {

class ContactSetManager {
  public:
    // The backends to schedule (owned by the simulation, which outlives this).
    void start(const Settings& settings, DynamicsBackend& dynamics, KinematicsBackend& kinematics);
    // Before each step: makes the set in use valid for it. `maxSpeed` is the fastest geometry point
    // after the previous step (sizes the margin of new detections).
    void prepareStep(const Settings& settings, unsigned long long step, float maxSpeed, TimingStats& timing);
    // After prepareStep: how many steps may run as one batch before the next prepareStep
    // (DetectionSchedule::stepsBeforeReview).
    unsigned long long stepsBeforeReview(unsigned long long step, bool async, unsigned int pollSteps) const {
        return m_schedule.stepsBeforeReview(step, async, pollSteps);
    }
    // After each step (or batch): the largest travel of any owner since the current set's snapshot.
    void afterStep(double maxTravel) { m_schedule.afterStep(maxTravel); }
    // Waits for the order in flight, if any, and takes its result if it may serve
    // (DoDynamicsThenSync, and before host-side edits).
    void sync(unsigned long long step, TimingStats& timing);
    // Between steps, for host-side edits of the contacts (persistence, contact wildcards): takes the
    // result in flight, then detects now if the set in use could miss a contact of the current state.
    void bringUpToDate(const Settings& settings, unsigned long long step, float maxSpeed, TimingStats& timing);
    // The state is about to be replaced (a host-side edit): the order in flight, detected from the
    // state being replaced, is waited for and dropped, so the kinematics side is idle.
    void dropOrderInFlight();
    // A host-side edit of the state: detect afresh before the next step; results in flight are stale.
    void invalidate() { m_schedule.invalidate(); }

    // Called just before each detection takes its snapshot of the state (synchronous or ordered):
    // the simulation checks the family conditions there (ChangeFamilyWhen). Empty: nothing.
    std::function<void()> beforeDetection;
    // Called with a detection's pair count before its set replaces the one in use: the simulation
    // checks there that the memory holds it (a deme::Error otherwise, with nothing changed). Empty:
    // nothing.
    std::function<void(size_t)> beforeInstall;
    // The host state's periodic box, for a sheared cell's orders (its shearTime is the time of the
    // state the orders are taken from).
    const PeriodicBox* period = nullptr;

    unsigned int nMax() const { return m_schedule.nMax(); }
    double margin() const { return m_schedule.margin(); }
    CollaborationStats& stats() { return m_stats; }
    const CollaborationStats& stats() const { return m_stats; }
    const UpdateFrequency& frequency() const { return m_schedule.frequency(); }
    void restoreFrequency(const UpdateFrequency::Learned& l) { m_schedule.restoreFrequency(l); }
    DetectionSchedule::Progress progress() const { return m_schedule.progress(); }
    void resume(const DetectionSchedule::Progress& p) { m_schedule.resume(p); }

  private:
    DetectionOrder orderFor(const Settings& settings, unsigned long long step, float maxSpeed) const;
    void limitShearedAge(const Settings& settings);
    void detectNow(const Settings& settings, unsigned long long step, float maxSpeed, TimingStats& timing);
    void consider(const DetectionReport& r, unsigned long long step, TimingStats& timing);
    void account(const DetectionReport& r, TimingStats& timing);
    void install(const DetectionReport& r, TimingStats& timing);

    DynamicsBackend* m_dynamics = nullptr;
    KinematicsBackend* m_kinematics = nullptr;
    DetectionSchedule m_schedule;
    bool m_configured = false;
    CollaborationStats m_stats;
};

}  // namespace deme
