// Keeps the dynamics side supplied with a valid active-contact set (ACS), detected synchronously on
// the dynamics thread or asynchronously by the kinematics thread (paper §2.1).
//
// Validity: an ACS detected from a snapshot with margin m stays valid while no owner has travelled
// more than m since that snapshot (see kinematics/ContactDetection.h for the no-miss bound). The
// integrator reports the largest travel every step; the manager never lets a step run on an expired
// set: it waits for the set in flight or detects on the spot.
#pragma once

#include <memory>
#include <vector>

#include "kinematics/ContactDetection.h"
#include "runtime/CollaborationStats.h"
#include "runtime/DetectionSchedule.h"
#include "runtime/FamilyRules.h"
#include "runtime/KinematicsWorker.h"
#include "runtime/Settings.h"
#include "runtime/TimingStats.h"

namespace deme {

class ContactSetManager {
  public:
    ~ContactSetManager();
    void start(const SimState& s, const Settings& settings, const BinGrid& grid);
    // Before each step: makes s.contacts a valid set for it. `maxSpeed` is the fastest geometry point
    // after the previous step (sizes the margin of new detections).
    void prepareStep(SimState& s, const Settings& settings, const FamilyRules& families, unsigned long long step,
                     float maxSpeed, TimingStats& timing);
    // After each step: the largest travel of any owner since the current set's snapshot.
    void afterStep(double maxTravel) { m_schedule.afterStep(maxTravel); }
    // Waits for the kinematics thread to finish its order and takes the result (DoDynamicsThenSync).
    void sync(SimState& s, unsigned long long step, TimingStats& timing);
    // Between steps, for host-side edits of the contacts (persistence, contact wildcards): takes the
    // result in flight, then detects now if the set in use could miss a contact of the current state.
    void bringUpToDate(SimState& s, const Settings& settings, const FamilyRules& families, unsigned long long step,
                       float maxSpeed, TimingStats& timing);
    // A host-side edit of the state: detect afresh before the next step; results in flight are stale.
    void invalidate() { m_schedule.invalidate(); }
    const std::vector<double>& travelBaseline() const { return m_baseline; }
    unsigned int nMax() const { return m_schedule.nMax(); }
    double margin() const { return m_schedule.margin(); }
    CollaborationStats& stats() { return m_stats; }
    const CollaborationStats& stats() const { return m_stats; }
    const UpdateFrequency& frequency() const { return m_schedule.frequency(); }

  private:
    void detectNow(SimState& s, const Settings& settings, const FamilyRules& families, unsigned long long step,
                   float maxSpeed, TimingStats& timing);
    void considerResult(SimState& s, DetectionResult& r, unsigned long long step, TimingStats& timing);
    void install(SimState& s, DetectedContacts& pairs, unsigned long long snapshotStep, double margin,
                 TimingStats& timing);

    std::unique_ptr<KinematicsWorker> m_worker;
    ContactDetector m_detector;  // for detections on the dynamics thread
    BinGrid m_grid;
    DetectionSchedule m_schedule;
    CollaborationStats m_stats;
    std::vector<double> m_baseline, m_orderBaseline;  // owners' travel at the set's / the order's snapshot
    DetectionResult m_result;
};

}  // namespace deme
