// The dynamics side (dT) of the CUDA backend: the state lives in device memory while DoDynamics runs;
// the mesh contact rule, the force pass, integration and history mapping run as kernels compiled
// at run time by NVRTC from the same per-item code the CPU's loops call (docs/cuda-backend.md), on
// dT's own stream. The step loop and the contact-set schedule above it are the engine's one
// (runtime/Simulation, runtime/ContactSetManager); contact detection is CudaKinematics'.
//
// The host SimState stays the record of owners and geometry between calls: upload() copies it to the
// device after Initialize and after host-side edits, download() copies the evolved state back when
// the host needs it. The contact set lives on the device: downloadContacts() copies it for a caller
// that reads it, upload() replaces it only after the host edited the set itself. Files: CudaDynamics.cpp (state copies), CudaStepBatch.cpp (the steps, in batches replayed from
// a captured step), CudaContactSets.cpp (installing a detected set), CudaDynamicsSetup.cpp (the
// kernels' compilation).
#pragma once

#include <memory>
#include <string>

#include "backend/cuda/CudaModule.h"
#include "backend/cuda/DeviceForceModel.h"
#include "backend/cuda/DeviceHistoryPool.h"
#include "backend/cuda/DeviceHistoryMapping.h"
#include "backend/cuda/DevicePrimitives.h"
#include "backend/cuda/DeviceState.h"
#include "backend/cuda/LaunchList.h"
#include "backend/cuda/StepGraph.h"
#include "backend/cuda/kernels/KernelArgs.cuh"
#include "forcemodel/ModelLayout.h"
#include "runtime/Backends.h"
#include "state/FamilyStepMotion.h"

namespace deme::cuda {

class CudaKinematics;

class CudaDynamics : public DynamicsBackend {
  public:
    // Compiles (or loads from the cache) the kernels for GPU `device`, the force model's included.
    CudaDynamics(int device, const ModelLayout& model);
    ~CudaDynamics() override;
    CudaDynamics(const CudaDynamics&) = delete;
    CudaDynamics& operator=(const CudaDynamics&) = delete;
    // The kinematics side whose results install() takes (made after this, on dT's stream).
    void setKinematics(CudaKinematics* kinematics) { m_kinematics = kinematics; }

    void upload(const SimState& s, bool withContacts) override;
    void download(SimState& s) override;
    void downloadContacts(SimState& s) override;
    void downloadResults(SimState& s) override;
    void gatherOwnerLoads(const std::vector<bodyID_t>& owners, float3* force, float3* torque) override;
    void uploadTrackerLoads(const SimState& s) override;
    void beginRun(const Settings& settings, const FamilyRules& families) override;
    StepBatchResult steps(const StepBatchRequest& batch, const Settings& settings, const FamilyRules& families,
                          TimingStats& timing) override;
    void downloadStepFlags(std::vector<uint8_t>& flags) override;
    size_t applyFamilyConditions(double time, const FamilyRules& families) override;
    void markOrderBaseline(bool installedBeforeNextStep) override;
    double maxTravelSinceOrder() override;
    void install(const DetectionReport& report, TimingStats& timing) override;
    bool beforeDetectNow() override;
    bool trimsBeforeDetection(size_t pairs) const override { return pairs * sizeof(bodyID_t) > m_smallSetBytes; }
    size_t numContacts() const override { return m_numContacts; }
    // Checkpoint and restart (CudaCheckpoint.cpp).
    bool contactSetResumable() const override;
    bool resumeContactSet(const SimState& s) override;
    std::string description() const override;
    std::string launchReport() const override;
    bool onGpu() const override { return true; }
    size_t memoryAvailable() const override;
    void countRunMemory(size_t bytes[NUM_MEMORY_GROUPS]) const override;
    size_t memoryFree() const override { return memoryAvailable(); }
    size_t expectedHistorySlots(size_t pairs, unsigned int W) const override;
    size_t expectedLateSlots(size_t pairs, unsigned int W) const override;
    bool keepsPersistentFlags() const override { return !m_contacts[m_current].persistent.empty(); }

    // What kinematics orders snapshot, on this stream.
    const DeviceState& state() const { return m_state; }
    Stream stream() const { return m_stream; }
    int device() const { return m_device; }
    const std::string& deviceName() const { return m_name; }
    double kernelCompileSeconds() const { return m_compileSeconds; }
    bool kernelsFromCache() const { return m_fromCache; }

  private:
    // The slots of a set of `pairs` pairs expected to hold a history (DENSE_HISTORY: the set will be
    // dense), for expectedHistorySlots and expectedLateSlots.
    size_t expectedSlotsWithHistory(size_t pairs, unsigned int W) const;
    void select() const;
    void compileKernels(const ModelLayout& layout);
    void prepareFamilyMotion(const FamilyRules& families);
    // Compiles generated source (a family kernel) for this GPU, found in the kernel cache after the
    // first time; the module keeps the kernel alive.
    void compileGenerated(const char* program, const std::string& source, const char* kernelName, CudaModule& module,
                          CudaKernel& kernel);
    void refreshView();
    // Per-contact forces are stored in the memory of the idle set's wildcards, dead between two
    // installs (CudaContactSets.cpp): lent before a storing step, given back before an install or
    // an upload overwrites either set.
    void lendIdleMemoryToForces();
    void returnForceMemory();
    // Writes one step's launches into `list` (CudaStepBatch.cpp): per-contact forces stored or not;
    // `afterPass`: only the kernels after the force pass (a paused step's rest).
    void recordStep(LaunchList& list, const Settings& settings, bool storeContactForces, bool afterPass = false);
    // The pooled history of the set in use (CudaHistoryPool.cpp): whether it is pooled; its pool
    // grown to `capacity` slots, contents kept (forces too where a storing step keeps them, or
    // `withForces`: a storing step paused in its pass); grown
    // before a batch where it is nearly full; and a step paused for room (the pool's counters read
    // back after the batch) finished: the pool grown, the pending pairs' histories made, the step's
    // rest run. The host's copy of a pooled set's history and forces, per pair.
    bool historyPooled() const { return m_pools[m_current].active; }
    void growHistoryPool(size_t capacity, bool withForces);
    void makeHistoryRoomBeforeBatch();
    void finishPausedStep(const Settings& settings, bool storing);
    void downloadPooledHistory(ContactArrays& c);
    void resetHistoryPoolControl(uint32_t used);
    [[noreturn]] void lateTableFull() const;
    // The owners and spheres a step integrates and places (CudaStepSubset.cpp).
    void updateStepSubset();
    void updateLoadOwners(bool flagStepped);

    int m_device = 0;
    std::string m_name;
    Stream m_stream = nullptr;  // dT's stream: every step kernel and copy of the dynamics side
    CudaModule m_dynamicsModule, m_exchangeModule;
    CudaKernel kBeginBatch, kClearLoads, kResolveMesh, kIntegrate, kPlaceAndFinish, kIntegrateAndPlace, kMaxTravelSince,
        kTravelSinceOrder, kAnyOwnerAtRest, kSteppedFlags, kSteppedScatter, kMarkContactOwners, kScatterFlagged,
        kFlagListed, kGatherOwnerLoads;
    // The batch's control block (dynamics/StepBatch.h) on the device, and its pinned host copy.
    DeviceBuffer<StepBatchControl> m_control;
    StepBatchControl* m_controlHost = nullptr;
    DeviceBuffer<unsigned int> m_blocksDone;  // the step's last kernel's count of finished blocks
    DeviceBuffer<float> m_componentSpeed;     // and its analytical components' surface speeds
    // Owner o's spheres are [start[o], start[o + 1]): for deme_integrate_and_place, which a step of
    // a scene without triangles uses unless DEME_CUDA_FUSED_STEP is "0" (m_fusedStep).
    DeviceBuffer<uint32_t> m_ownerSphereStart;
    bool m_fusedStep = true;
    bool m_analyticalInBlock = true;  // DEME_CUDA_ANALYTICAL_IN_BLOCK (StepGraph.h)
    bool m_inputsBeforeWait = true;   // DEME_CUDA_INPUTS_BEFORE_WAIT (StepGraph.h)
    // One step's launches, without and with stored contact forces, and their graphs: plain steps
    // go in graphs of m_graphSteps steps (StepGraph.h), the rest of a batch one step a graph.
    LaunchList m_plainStep, m_storingStep;
    StepGraph m_plainGraph, m_plainGraphs, m_storingGraph;
    bool m_useGraphs = true;
    unsigned int m_graphSteps = 8;
    bool m_overlapLaunches = false;  // programmatic dependent launch within a step's list
    // The families' prescriptions, compiled from the user's expressions (recompiled when they change).
    CudaModule m_familyModule;
    CudaKernel kFamilyMotion;
    std::string m_familySource;
    // The family conditions (ChangeFamilyWhen), compiled when they change (CudaFamilyChanges.cpp).
    CudaModule m_conditionModule;
    CudaKernel kFamilyConditions;
    std::string m_conditionSource;
    DeviceBuffer<unsigned int> m_changedCount, m_anyOwnerAtRest;
    double m_compileSeconds = 0.0;
    bool m_fromCache = true;
    // DEME_CUDA_PROFILE_FROM_STEP: the step at which a profiler's capture starts (docs/gpu-tests.md).
    unsigned long long m_profileFromStep = ~0ull, m_steps = 0;
    // The contact force model's kernel and data, and the history mapping of each new set.
    DeviceForceModel m_model;
    DeviceHistoryMapping m_history;
    DevicePrimitives m_prim;
    CudaKinematics* m_kinematics = nullptr;

    DeviceState m_state;
    DeviceContacts m_contacts[2];  // the set in use and the one a detection fills
    int m_current = 0;
    size_t m_numContacts = 0;           // (past 2^32: a pair's index is 64 bits on the GPU)
    bool m_forcesInIdleMemory = false;  // the set in use's forces hold the idle set's wildcards' memory
    // The set in use holds only the pairs it hands to the next set (beforeDetectNow), until an
    // installation or an upload replaces it: it serves no step, and no checkpoint resumes it.
    bool m_setTrimmed = false;
    size_t m_pairsForSlotShare = 0;  // the set's pairs before any trim (expectedHistorySlots)
    bool m_asyncDetection = true;  // the call's detection mode (beginRun): the outbox is kept where it is
    // A contact set whose id arrays take at most this many bytes each is kept whole before a
    // synchronous detection, and its outbox kept between detections: there the memory does not
    // count, and a lab-scale run that detects thousands of times a second would pay for the trim's
    // round trip and for allocating the outbox anew (runtime/RebuiltArrays.h).
    size_t m_smallSetBytes = KEEP_REBUILT_ARRAYS_UP_TO;
    // Each set's pooled history (DeviceHistoryPool.h), the pool's counters (on the device and as
    // last read back) and the rule that chooses the form.
    DeviceHistoryPool m_pools[2];
    DeviceBuffer<HistoryPoolControl> m_poolControl;
    HistoryPoolControl m_poolControlHost{};
    HistoryPoolPolicy m_poolPolicy;
    unsigned long long m_installs = 0, m_pooledInstalls = 0, m_historyPauses = 0;  // for launchReport()
    // Owners' travel (since the set in use's snapshot: the state's) at the snapshot of the order in
    // flight.
    DeviceBuffer<float> m_orderBaseline;  // sized by an asynchronous order only
    bool m_orderAtInstall = false;        // the set to be installed is a synchronous detection's
    DeviceBuffer<FamilyStepMotion> m_motion;
    DeviceBuffer<StepReduction> m_reduction;
    DeviceBuffer<unsigned long long> m_maxTravelBits;
    // The pairs that touched in the last step run (0 before any): whether a set installed now is
    // mostly apart (StateView::voxelPretest).
    unsigned long long m_lastRealContacts = 0;
    // DEME_CUDA_VOXEL_PRETEST: "0" never (0), "1" for every set the layout allows (1: the tests'
    // bit-for-bit check, timing trials), unset by the rule (-1). Read once, as the other switches.
    int m_voxelPretestForced = -1;
    // gatherOwnerLoads's rows and their forces then torques (let go after a batch of more than
    // GATHER_KEPT_ROWS rows).
    static constexpr size_t GATHER_KEPT_ROWS = 4096;
    DeviceBuffer<bodyID_t> m_gatherIds;
    DeviceBuffer<float3> m_gatheredLoads;
    // The active box: the owners a step integrates (all but fixed ones at rest) and their spheres,
    // rebuilt at the first step after an upload, a detection's install, a family change or the
    // start of a call, the only times families, velocities of fixed owners and the set change.
    bool m_subsetStale = true, m_subsetAll = true;
    bool m_anyFamilyFixed = true;   // the call's rules (beginRun): without a fixed family every owner steps
    bool m_loadOwnersStale = true;  // the set changed: the owners whose loads a step clears follow
    DeviceBuffer<unsigned int> m_ownerStepped, m_ownerStepOffset, m_sphereStepped, m_sphereStepOffset;
    DeviceBuffer<bodyID_t> m_steppedOwners, m_steppedSpheres, m_loadOwners;
    unsigned int m_numSteppedOwners = 0, m_numSteppedSpheres = 0, m_numLoadOwners = 0;

    // Host-side copies of what the loop needs.
    StateView m_view{};
    unsigned int m_W = 0;
    double m_domainDiagonal = 0.0;
};

}  // namespace deme::cuda
