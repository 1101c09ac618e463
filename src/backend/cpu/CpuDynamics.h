// The dynamics side (dT) of the CPU backend: steps the host state itself with OpenMP loops over the
// per-item code (mesh contact rule, force pass, force reduction, integration) and installs the
// contact sets its kinematics side detects. The step loop and the schedule above it are the
// engine's one (runtime/Simulation, runtime/ContactSetManager).
#pragma once

#include <array>
#include <vector>

#include "backend/cpu/CpuForceModel.h"
#include "backend/cpu/Integration.h"
#include "runtime/Backends.h"
#include "state/FamilyStepMotion.h"

namespace deme {

class CpuKinematics;

class CpuDynamics : public DynamicsBackend {
  public:
    // Steps `s` (the host state: nothing is copied) with `model`; installs what `kinematics` detects.
    CpuDynamics(SimState& s, CpuForceModel model, CpuKinematics& kinematics);

    void upload(const SimState& s, bool withContacts) override;
    void download(SimState&) override {}
    // The steps' history, pooled or not, into the form every host reader takes (HistoryForm.h).
    void downloadContacts(SimState& s) override;
    void uploadTrackerLoads(const SimState&) override {}
    void beginRun(const Settings&, const FamilyRules&) override { m_subsetStale = true; }
    StepBatchResult steps(const StepBatchRequest& batch, const Settings& settings, const FamilyRules& families,
                          TimingStats& timing) override;
    void downloadStepFlags(std::vector<uint8_t>& flags) override { flags = m_s.integrationScratch.flags; }
    size_t applyFamilyConditions(double time, const FamilyRules& families) override;
    void markOrderBaseline(bool installedBeforeNextStep) override;
    double maxTravelSinceOrder() override;
    void install(const DetectionReport& report, TimingStats& timing) override;
    bool beforeDetectNow() override;
    size_t numContacts() const override { return m_s.contacts.size(); }
    bool contactSetResumable() const override { return !m_setTrimmed; }
    bool resumeContactSet(const SimState& s) override;
    std::string description() const override;
    bool onGpu() const override { return false; }
    void countHostMemory(MemoryStats& m) const override;
    size_t memoryAvailable() const override;
    void countRunMemory(size_t bytes[NUM_MEMORY_GROUPS]) const override;
    size_t memoryFree() const override;
    size_t expectedHistorySlots(size_t pairs, unsigned int W) const override;
    bool keepsPersistentFlags() const override { return !m_s.contacts.persistent.empty(); }
    // The share of the set in use's pairs with a history where it is pooled; -1 where it is dense.
    double historyShare() const;

    const CpuForceModel& model() const { return m_model; }

  private:
    // Whether the force model may set a contact's persistent flag (a custom one may).
    bool modelWritesPersistent() const { return !m_model.layout.builtIn(); }
    // One step from `time` (per-contact forces are stored in every step).
    StepOutcome step(double time, const Settings& settings, const FamilyRules& families, TimingStats& timing,
                     ForceStore store);

    SimState& m_s;
    CpuForceModel m_model;
    CpuKinematics& m_kinematics;
    std::array<FamilyStepMotion, NUM_FAMILIES> m_stepMotion;
    // The owners a step integrates (all but the dormant ones at rest), and whether families or
    // their rules may have changed since it was made.
    IntegrationSubset m_subset;
    bool m_subsetStale = true;
    size_t m_lastRealContacts = 0;  // pairs touching in the last force pass (how to store forces)
    // Whether the set's history was made dense outside an installation (a host reader, an edit, a
    // restart) and its form is to be chosen before the next steps (backend/cpu/HistoryForm.h).
    bool m_chooseHistoryForm = true;
    // Whether the set holds only the pairs it hands to the next one (beforeDetectNow), until an
    // installation or an upload replaces it: then it serves no step and no restart.
    bool m_setTrimmed = false;
    double m_historyShareBeforeTrim = 0.0;  // its pairs' share with a history before the trim (-1: dense)
    // Owners' travel (since the set in use's snapshot) at the snapshot of the order in flight: empty
    // while there is none, and for a synchronous detection's order, whose snapshot is the travel at
    // its installation (m_orderAtInstall).
    std::vector<float> m_orderBaseline;
    bool m_orderAtInstall = false;
    void releaseOrderBaseline();
};

}  // namespace deme
