// The running simulation: owns the host state (the record between calls) and the backends, and runs
// the engine's one step loop over them (advance) with the one contact-set schedule
// (ContactSetManager). Which backend runs the steps (CPU or CUDA) is decided at start().
#pragma once

#include <memory>

#include "forcemodel/ModelLayout.h"
#include "kinematics/BinGrid.h"
#include "runtime/Backends.h"
#include "runtime/ContactSetManager.h"
#include "runtime/FamilyRules.h"
#include "runtime/MemoryEstimate.h"
#include "runtime/RunMonitor.h"
#include "runtime/SceneFingerprint.h"
#include "runtime/Settings.h"
#include "runtime/TimingStats.h"
#include "state/SimState.h"

namespace deme {

class Simulation {
  public:
    Simulation();
    ~Simulation();
    Settings settings;
    FamilyRules families;

    bool initialized() const { return m_initialized; }
    // Takes over an assembled state, chooses the backend and loads the force model for it; the first
    // step detects contacts.
    void start(SimState&& state, const ModelLayout& model);
    // Advances n steps of settings.dt, or fewer if a hook of monitor() stops the call (monitor().stopped()).
    void advance(unsigned long long n);
    // Progress reports and interrupt requests polled between steps.
    RunMonitor& monitor() { return m_monitor; }
    const RunMonitor& monitor() const { return m_monitor; }

    double time() const { return m_time; }
    // The state for reading; on the GPU backend it is brought back from the device first if the
    // device has moved on. Without the contact set: on the GPU backend s.contacts may be empty or
    // behind (the set lives on the device, and the host keeps no copy of it between calls).
    const SimState& state() const;
    // The same with the contact set (output of contacts, stress).
    const SimState& stateWithContacts() const;
    // The same with every owner's results too (state/SimState.h: a GPU run's host holds them only
    // while fetched): checkpoints, and edits that renumber owners.
    const SimState& wholeState() const;
    // The state for editing (tracker setters, family changes): the backend's copy is replaced by it
    // before the next step, which re-detects contacts; the backend's contact set and its history
    // stay.
    SimState& editState();
    // For edits of the contact set itself (contact wildcards and persistence): the backend's set is
    // replaced by the host's too.
    SimState& editStateWithContacts();
    // For edits that add or remove owners (scene edits): the same with every owner's results
    // (wholeState), which the edit renumbers and the upload sends.
    SimState& editWholeState();
    // The tracker loads for adding to (AddAcc), made on the first: they go to the backend with the
    // next call by themselves, without replacing its state.
    TrackerLoadArrays& trackerLoads() {
        m_state.trackerLoads.prepare(m_state.owners.size());
        return m_state.trackerLoads;
    }
    // Counts the host keeps itself (scene edits happen on the host): no download.
    size_t numSpheres() const { return m_state.spheres.size(); }
    size_t numClumps() const { return m_state.numClumps; }
    const TimingStats& timing() const { return m_timing; }
    size_t numRealContacts() const { return m_realContacts; }
    size_t numSphereSphereContacts() const { return m_realSphereSphere; }
    double currentMargin() const { return m_contacts.margin(); }
    unsigned int updateFreq() const { return m_contacts.nMax(); }  // the n_max in use
    const ContactSetManager& contactSets() const { return m_contacts; }
    // The counters only; the schedule's own measurements (latency, n_max) go on.
    void clearCollaborationStats() { m_contacts.stats() = CollaborationStats{}; }
    const ModelLayout& forceModel() const { return m_model; }
    // Makes s.contacts the set the next step would start from (waiting for the kinematics side or
    // detecting now), for host-side edits of the contacts.
    void refreshContactSet();
    // Resolves settings.detectionMode into settings.asyncDetection and sizes the dynamics thread
    // team accordingly.
    void applyDetectionMode();
    // The form a contact set of `pairs` pairs will take (its history's, and whether synchronous
    // detection trims the set before each detection), for the memory checks.
    ContactSetForm contactSetForm(size_t pairs) const;
    // Lets the kinematics side finish its order and installs the result.
    void syncContactDetection();
    const BinGrid& binGrid() const { return m_grid; }
    // "CPU, 2 threads" or "GPU 0 (NVIDIA H200)".
    std::string backendDescription() const { return m_backends.dynamics ? m_backends.dynamics->description() : ""; }
    std::string launchReport() const { return m_backends.dynamics ? m_backends.dynamics->launchReport() : ""; }
    // Host memory by group: the state's arrays and the backends' own (runtime/MemoryAccounting.cpp).
    MemoryStats hostMemory() const;

    // Host-side changes to the state (tracker setters, family changes) call this so that the next
    // step re-detects contacts instead of trusting the old margin.
    void invalidateContacts();

    // Scene edits between calls (runtime/SceneEdits.h): clumps inserted (`part`: new clumps only,
    // assembled in this domain) or removed (remove[o] != 0 for internal owner o); the bin grid is
    // re-sized for an insertion, and the backend gets the whole new state before the next step.
    void insertClumps(const SimState& part);
    size_t removeClumps(const std::vector<uint8_t>& remove);

    // Owner queries used by trackers, inspectors and writers.
    double3 ownerPos(size_t owner) const;
    // The last step's contact force and torque (global frame) of owners[i] (internal ids), into
    // force[i] and torque[i] (either may be null): from the host where it holds the results, else
    // gathered on the device (a tracker's rows, without bringing every owner's back).
    void ownerLoads(const std::vector<bodyID_t>& owners, float3* force, float3* torque) const;
    // Before a call's steps: where the "remove" exit policy is on, the frame reads parked clumps'
    // centres from then on (DomainFrame::parks, state/OwnerCentre.h).
    void allowParking();
    void setOwnerPos(size_t owner, const double3& p, const char* call);
    float ownerMass(size_t owner) const { return m_state.massProps.mass[m_state.owners.inertia[owner]]; }
    float3 ownerMOI(size_t owner) const { return m_state.massProps.moi[m_state.owners.inertia[owner]]; }

    void log(Verbosity level, const std::string& msg) const;

    // Checkpoint and restart (io/Checkpoint.h). What the run carries besides its state: the clock,
    // the step counter, what sizes the next margin, what n_max has adapted to, and where the contact
    // set in use stands (its snapshot step, margin, and whether it can go on serving: the owners'
    // travel since its snapshot is in the state).
    struct Resumable {
        double time = 0.0;
        unsigned long long step = 0;
        float lastMaxSpeed = 0.f;
        uint64_t realContacts = 0, realSphereSphere = 0;
        UpdateFrequency::Learned frequency;
        DetectionSchedule::Progress contactSet;
        bool contactSetResumable = false;  // false: the restart detects afresh
    };
    Resumable resumable() const;
    // The scene as Initialize assembled it (a checkpoint is read only into the same scene).
    const SceneFingerprint& initialScene() const { return m_initialScene; }
    // Replaces the whole host state and the counters (ReadCheckpoint). The backend takes the state
    // before the next step and goes on with the restored contact set and its schedule, so that
    // detections fall on the steps they would have; a backend that cannot (or a checkpoint from
    // one that cannot) detects afresh instead, and the new set takes the restored set's history.
    void restore(SimState&& state, const Resumable& r);

  private:
    // Gives the backend the host state if the host edited it since (and re-detects then).
    void uploadIfEdited();
    void clearTrackerLoads();
    [[noreturn]] void reportFault(const StepOutcome& out) const;
    // The "remove" domain exit policy: takes the clumps the steps parked out of the state (a host
    // edit, sent at the next upload); returns how many.
    size_t removeParkedClumps();

    mutable SimState m_state;
    ModelLayout m_model;
    // Whether the backend's copy is behind the host's (needs an upload) or the host's behind the
    // backend's (needs a download; never on the CPU, which steps the host state itself).
    bool m_backendStale = true;
    mutable bool m_hostStale = false;
    // The same for the contact set, which on a GPU the host copies only when a caller reads it.
    bool m_backendContactsStale = true;
    mutable bool m_hostContactsStale = false;
    // After steps or a detection on a GPU: the host's copy is behind, and its contact arrays are
    // let go (a GPU run's host keeps no copy of the set between calls).
    void markHostBehind();
    TimingStats m_timing;
    BinGrid m_grid{};
    double m_time = 0.0;
    unsigned long long m_step = 0;
    bool m_initialized = false;
    size_t m_realContacts = 0, m_realSphereSphere = 0;
    float m_lastMaxSpeed = 0.f;
    RunMonitor m_monitor;
    SceneFingerprint m_initialScene;
    MemoryEstimate m_memoryEstimate;
    // A restored contact set and schedule for the next upload (restore()); none once taken.
    std::unique_ptr<Resumable> m_resume;
    ContactSetManager m_contacts;
    Backends m_backends;  // last: the kinematics thread stops before the state goes
};

}  // namespace deme
