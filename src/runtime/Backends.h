// The small interface between the one step loop (runtime/Simulation) and scheduler
// (runtime/ContactSetManager) and the backends that run them: the CPU (backend/cpu, OpenMP loops)
// and CUDA (backend/cuda, kernels). Both implement it with loops over the same per-item functions
// (kinematics/, dynamics/); everything that decides -- when to detect, wait or swap contact sets,
// what a step does in which order, when a run stops -- is above it and written once.
//
// Kinematics (kT, paper §2.1): contact detection, on its own thread beside the steps (submit, then
// try-take or wait-and-take) or on the spot (detectNow). Dynamics (dT): the state, the steps, and
// the installation of a detected contact set (history mapping).
#pragma once

#include <deme/Error.h>
#include <deme/MemoryStats.h>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dynamics/StepBatch.h"
#include "kinematics/BinGrid.h"
#include "runtime/FamilyRules.h"
#include "runtime/MemoryEstimate.h"
#include "runtime/Settings.h"
#include "runtime/TimingStats.h"
#include "state/SimState.h"

namespace deme {

struct ModelLayout;

// A detection from the state of dynamics step `step`, geometries enlarged by `margin`.
struct DetectionOrder {
    unsigned long long step = 0;
    unsigned long long generation = 0;  // host edits counted by the scheduler; older results are stale
    double margin = 0.0;  // each owner may travel this far before the set expires
    // A sheared periodic cell (Lees–Edwards): the snapshot's time (its image offset), and how far
    // images across the z faces move towards each other while the set serves (n_max steps at the
    // shear velocity), which travel does not count: detection enlarges geometries by margin plus half
    // of it (DetectionOrder::detectionMargin).
    double shearTime = 0.0;
    double imageDrift = 0.0;
    double detectionMargin() const { return margin + 0.5 * imageDrift; }
};

// What one detection found; the pairs themselves stay with the backend until installed.
struct DetectionReport {
    DetectionOrder order;
    size_t numPairs = 0;
    double binningSeconds = 0.0, searchSeconds = 0.0;
};

// What one step reports.
struct StepOutcome {
    size_t realContacts = 0, realSphereSphere = 0;  // pairs with overlap > 0 after the step's force pass
    float maxSpeed = 0.f;                           // fastest geometry point (sizes the next margin)
    double maxTravel = 0.0;                         // largest travel of any owner since the set in use was detected
    bool fault = false;                             // some owner diverged or left the domain (faultOwner, faultFlags)
    size_t faultOwner = 0;                          // lowest internal owner id with a fault
    uint8_t faultFlags = 0;                         // OwnerStepFlag bits of that owner
    unsigned int kernelError = 0, kernelErrorItem = 0;  // GPU only: KernelError bits and the sphere
    size_t parkedOwners = 0;  // clumps that left under the "remove" policy, parked (dynamics/OwnerStep.h)
};

// A step's outcome as the end-of-step rule tallies it (dynamics/StepBatch.h), and back (the fault's
// flags are the backend's to fill in).
inline StepTally tallyOf(const StepOutcome& o) {
    StepTally t;
    t.maxTravel = o.maxTravel;
    t.maxSpeed = o.maxSpeed;
    t.firstFault = o.fault ? (unsigned int)o.faultOwner : NO_FAULT;
    t.errorFlags = o.kernelError;
    t.errorItem = o.kernelErrorItem;
    t.realContacts = o.realContacts;
    t.realSphereSphere = o.realSphereSphere;
    t.parkedOwners = (unsigned int)o.parkedOwners;
    return t;
}
inline StepOutcome outcomeOf(const StepTally& t) {
    StepOutcome o;
    o.realContacts = (size_t)t.realContacts;
    o.realSphereSphere = (size_t)t.realSphereSphere;
    o.parkedOwners = t.parkedOwners;
    o.maxSpeed = t.maxSpeed;
    o.maxTravel = t.maxTravel;
    o.fault = t.firstFault != NO_FAULT;
    o.faultOwner = o.fault ? t.firstFault : 0;
    o.kernelError = t.errorFlags;
    o.kernelErrorItem = t.errorItem;
    return o;
}

// A batch of steps the dynamics side runs without the host looking in between (dynamics/StepBatch.h):
// at most `maxSteps` from `time` with the set in use (of margin `margin`), ended early after a step
// that lets that set expire or finds a fault.
struct StepBatchRequest {
    unsigned long long maxSteps = 1;
    double time = 0.0;
    double margin = 0.0;
    // Per-contact forces stored in the batch's last step (the host may read them after it), on
    // both backends; the other steps store none.
    bool storeContactForcesAtEnd = true;
};

struct StepBatchResult {
    unsigned long long steps = 0;        // completed (at least one)
    double time = 0.0;                   // the clock after them
    unsigned long long realContactSum = 0;  // pairs in contact, summed over the steps
    StepOutcome last;                    // the last completed step's
};

class KinematicsBackend {
  public:
    virtual ~KinematicsBackend() = default;
    // What detection reads and never changes during a run, from the host state (after Initialize
    // and every host-side edit). Only while no order is in flight.
    virtual void setGeometry(const SimState& s, const BinGrid& grid, const FamilyRules& families,
                             const Settings& settings) = 0;
    // Asynchronous detection: sends an order from the current state (snapshot taken now).
    virtual void submit(const DetectionOrder& order) = 0;
    // A finished result, if any (false: none yet). Rethrows a failure of the kinematics thread.
    virtual bool tryTake(DetectionReport& report) = 0;
    // Waits for the order in flight, then takes its result.
    virtual void waitAndTake(DetectionReport& report) = 0;
    // Synchronous detection from the current state (the dynamics side waits for it).
    virtual void detectNow(const DetectionOrder& order, DetectionReport& report) = 0;
    // Whether detection takes its time from the dynamics side's device (n_max then weighs its cost).
    virtual bool sharesDynamicsDevice() const = 0;
    // Whether a synchronous detection (detectNow) reads the dynamics side's state where it is, with no
    // snapshot copied: then a run that detects only so holds none (the memory estimate counts so).
    virtual bool detectsInPlace() const { return true; }
    // Whether a detection of `spheres` spheres may bin them by their centres where the rule allows
    // (kinematics/DetectionRules.h, centreReachFor): the memory estimate counts its bins so.
    virtual bool mayBinSpheresByCentre(size_t /*spheres*/) const { return true; }
    // Adds the host memory this backend holds of its own (MemoryStats::hostBytes).
    virtual void countHostMemory(MemoryStats& /*m*/) const {}
};

class DynamicsBackend {
  public:
    virtual ~DynamicsBackend() = default;
    // The host state becomes the one the steps run on (after Initialize and host-side edits). With
    // withContacts false the contact set the backend holds stays as it is (the host's copy of it may
    // be empty then): edits of owners and geometry leave the pairs and their history alone.
    virtual void upload(const SimState& s, bool withContacts) = 0;
    // The evolved state into `s`: owners, the kinematic cache and the model's wildcards; not the
    // contact set, which downloadContacts brings where a caller reads it.
    virtual void download(SimState& s) = 0;
    // The contact set in use (pairs, history, per-contact forces) into s.contacts.
    virtual void downloadContacts(SimState& s) = 0;
    // The owners' results (the RESULT fields of state/StateFields.h) into `s`, one per owner (zero
    // before the first step). The CPU's host state holds them always.
    virtual void downloadResults(SimState& /*s*/) {}
    // The last step's contact force and torque of owners[i] (internal ids) into force[i] and
    // torque[i] (either may be null), without bringing every owner's back: for a host that does not
    // hold the results (Simulation::ownerLoads), which the CPU's always does.
    virtual void gatherOwnerLoads(const std::vector<bodyID_t>& /*owners*/, float3* /*force*/, float3* /*torque*/) {
        throwError("DEMTracker", "internal: this backend's host state holds the owners' loads");
    }
    // Tracker loads (AddAcc) of `s` for the coming call, or zeros.
    virtual void uploadTrackerLoads(const SimState& s) = 0;
    // Before the steps of one DoDynamics call (the GPU compiles changed prescriptions here).
    virtual void beginRun(const Settings& settings, const FamilyRules& families) = 0;
    // Steps with the contact set in use, as one batch: per step, contact forces, their reduction
    // onto owners, integration and the cached poses; after each, the rule of dynamics/StepBatch.h.
    virtual StepBatchResult steps(const StepBatchRequest& batch, const Settings& settings,
                                  const FamilyRules& families, TimingStats& timing) = 0;

    // The OwnerStepFlag bits of every owner from the last step (dynamics/OwnerStep.h), after a step
    // that reported a fault: which owners left the domain.
    virtual void downloadStepFlags(std::vector<uint8_t>& flags) = 0;

    // Family changes on conditions (families.conditions(), ChangeFamilyWhen) checked for every owner
    // against the state now, at time `time`; returns how many owners changed family. Run just before
    // each detection's snapshot (runtime/ContactSetManager), so the new set is built for the new
    // families.
    virtual size_t applyFamilyConditions(double time, const FamilyRules& families) = 0;

    // Contact sets. The owners' travel (OwnerArrays::travel) counts from the snapshot of the set in
    // use. markOrderBaseline(): the owners' travel now is the snapshot of an order sent now.
    // `installedBeforeNextStep` (a synchronous detection's order): its snapshot is then the travel at
    // its installation, and a backend need keep no copy of it meanwhile (the CPU keeps none).
    virtual void markOrderBaseline(bool installedBeforeNextStep) = 0;
    // The largest travel of any owner since the last markOrderBaseline().
    virtual double maxTravelSinceOrder() = 0;
    // The result of the last order taken from the kinematics side becomes the set in use, with the
    // history of the set it replaces (wildcards, mesh state, persistent pairs); the owners' travel
    // counts from the order's snapshot from now on (what they travelled since it).
    virtual void install(const DetectionReport& report, TimingStats& timing) = 0;
    // A detection whose set is installed before the next step (synchronous) is about to run: what
    // only the steps read of the set in use may go now (the CPU's reduction index, rebuilt by the
    // installation, or by the next step if the installation fails), lowering the detection's peak.
    // Returns true where the set in use then serves no step (the CPU keeps only the pairs that
    // hand something to the next set): if the installation fails, the run detects afresh before
    // its next step, and a checkpoint holds no set to go on with.
    virtual bool beforeDetectNow() { return false; }
    // Whether beforeDetectNow may trim a set of `pairs` pairs (the GPU leaves small sets whole).
    virtual bool trimsBeforeDetection(size_t /*pairs*/) const { return true; }
    virtual size_t numContacts() const = 0;
    // Checkpoint and restart. contactSetResumable: whether the set in use could serve a restart (a
    // checkpoint then holds it, with the owners' travel since its snapshot in the state).
    // resumeContactSet: after upload(s), the set in use is s.contacts as it is (history and all, no
    // detection), its snapshot where s.owners.travel counts from. A backend that cannot answers
    // false, and the restart detects afresh (the trajectory does not depend on when detection runs).
    virtual bool contactSetResumable() const { return false; }
    virtual bool resumeContactSet(const SimState& /*s*/) { return false; }

    // The margin-free facts the messages and reports need.
    virtual std::string description() const = 0;  // "CPU, 2 threads", "GPU 0 (NVIDIA H200)"
    // How the steps were launched, for the timing report ("" where there is nothing to say).
    virtual std::string launchReport() const { return ""; }
    virtual bool onGpu() const = 0;
    // Adds the host memory this backend holds of its own (MemoryStats::hostBytes).
    virtual void countHostMemory(MemoryStats& /*m*/) const {}
    // The bytes a run may take where its steps keep their arrays, for the check at Initialize
    // (runtime/MemoryEstimate.h): the GPU's free memory; on the CPU what the machine has available
    // plus what the host state already holds. 0 where not known.
    virtual size_t memoryAvailable() const = 0;
    // What the run holds now where its steps keep their arrays, per group as ShowMemoryStats counts
    // it (the GPU's buffers of this process; the host state and this backend's own arrays), and the
    // memory still free there (0 where not known): for the check before a contact set grows
    // (runtime/MemoryEstimate.h, requireRoomForContactSet).
    virtual void countRunMemory(size_t bytes[NUM_MEMORY_GROUPS]) const = 0;
    virtual size_t memoryFree() const = 0;
    // The form the next contact set of `pairs` pairs (W wildcards a pair) is expected to keep its
    // history in, for the
    // memory checks (contactSetBytes): the slots of its pool where it will be pooled, DENSE_HISTORY
    // where it will hold W floats per pair. A first set has no history yet (a pool with its spare
    // slots only); a later one is expected to have as large a share of its pairs with one as the
    // set in use, and a dense set in use is expected to stay dense.
    virtual size_t expectedHistorySlots(size_t pairs, unsigned int W) const = 0;
    // Of those slots, the ones the pool keeps spare for pairs that take a history between
    // installations (the GPU sizes its late table to them: state/HistoryPool.h); 0 where none.
    virtual size_t expectedLateSlots(size_t pairs, unsigned int W) const {
        (void)pairs;
        (void)W;
        return 0;
    }
    // Whether the set in use keeps a persistent flag per pair (where some pair has one or the model
    // may set one; none before the first set), for the same checks: a set keeps them where the
    // model may set one or the set it is mapped from has them.
    virtual bool keepsPersistentFlags() const = 0;
};

// A backend's two sides, made together (each side knows its partner).
struct Backends {
    std::unique_ptr<DynamicsBackend> dynamics;
    std::unique_ptr<KinematicsBackend> kinematics;
};

// Made by backend/BackendFactory.cpp. `s` is the host state the CPU backend steps on (and that a GPU
// backend uploads from); the force model is loaded for the backend (compiled at run time for a
// custom model). Messages go through `log`. Throws deme::Error naming "Initialize" on failure.
Backends makeBackends(SimState& s, const ModelLayout& model, Settings& settings,
                      const std::function<void(Verbosity, const std::string&)>& log);

}  // namespace deme
