// The running simulation: owns the flat state and advances it step by step (the dynamics side);
// the contact-set manager supplies valid contact sets, from the kinematics thread or synchronously.
#pragma once

#include <array>
#include <memory>

#include "kinematics/ContactDetection.h"
#include "dynamics/Integration.h"
#include "forcemodel/ActiveForceModel.h"
#include "runtime/ContactSetManager.h"
#include "runtime/FamilyRules.h"
#include "runtime/RunMonitor.h"
#include "runtime/Settings.h"
#include "runtime/SimState.h"
#include "runtime/TimingStats.h"

namespace deme {

namespace cuda {
class DeviceSimulation;
}

class Simulation {
  public:
    Simulation();
    ~Simulation();
    Settings settings;
    FamilyRules families;

    bool initialized() const { return m_initialized; }
    // Takes over an assembled state and the force model; the first step detects contacts.
    void start(SimState&& state, ActiveForceModel&& model);
    // Advances n steps of settings.dt, or fewer if a hook of monitor() stops the call (monitor().stopped()).
    void advance(unsigned long long n);
    // Progress reports and interrupt requests polled between steps.
    RunMonitor& monitor() { return m_monitor; }
    const RunMonitor& monitor() const { return m_monitor; }

    double time() const { return m_time; }
    // The state for reading; on the GPU backend it is brought back from the device first if the
    // device has moved on.
    const SimState& state() const;
    // The state for editing (tracker setters, family changes): the device copy is replaced by it
    // before the next step.
    SimState& editState();
    // The state for adding tracker loads (AddAcc): they go to the device with the next call by
    // themselves, without replacing its state.
    SimState& trackerLoadState() {
        state();
        return m_state;
    }
    const TimingStats& timing() const { return m_timing; }
    size_t numRealContacts() const { return m_realContacts; }
    size_t numSphereSphereContacts() const { return m_realSphereSphere; }
    double currentMargin() const;
    unsigned int updateFreq() const;  // the n_max in use
    const ContactSetManager& contactSets() const { return m_contacts; }
    const ActiveForceModel& forceModel() const { return m_model; }
    // Makes s.contacts the set the next step would start from (waiting for the kinematics thread or
    // detecting now), for host-side edits of the contacts.
    void refreshContactSet();
    // Resolves settings.detectionMode into settings.asyncDetection and sizes the dynamics thread
    // team accordingly.
    void applyDetectionMode();
    // Lets the kinematics thread finish its order and installs the result.
    void syncContactDetection();
    const BinGrid& binGrid() const { return m_grid; }

    // Host-side changes to the state (tracker setters, family changes) call this so that the next
    // step re-detects contacts instead of trusting the old margin.
    void invalidateContacts();

    // Owner queries used by trackers, inspectors and writers.
    double3 ownerPos(size_t owner) const;
    void setOwnerPos(size_t owner, const double3& p, const char* call);
    float ownerMass(size_t owner) const { return m_state.massProps.mass[m_state.owners.inertia[owner]]; }
    float3 ownerMOI(size_t owner) const { return m_state.massProps.moi[m_state.owners.inertia[owner]]; }

    void log(Verbosity level, const std::string& msg) const;

  private:
    void clearTrackerLoads();
    void startDevice();
    void advanceOnDevice(unsigned long long n);
    [[noreturn]] void reportFault(const IntegrationResult& ir) const;

    mutable SimState m_state;
    // GPU backend: the device step loop; whether the device's copy is behind the host's (needs an
    // upload) or the host's behind the device's (needs a download).
    std::unique_ptr<cuda::DeviceSimulation> m_device;
    bool m_deviceStale = true;
    mutable bool m_hostStale = false;
    ActiveForceModel m_model;
    TimingStats m_timing;
    BinGrid m_grid;
    std::array<FamilyStepMotion, NUM_FAMILIES> m_stepMotion;
    double m_time = 0.0;
    unsigned long long m_step = 0;
    bool m_initialized = false;
    size_t m_realContacts = 0, m_realSphereSphere = 0;
    float m_lastMaxSpeed = 0.f;
    RunMonitor m_monitor;
    ContactSetManager m_contacts;  // last: its worker thread stops before the state goes
};

}  // namespace deme
