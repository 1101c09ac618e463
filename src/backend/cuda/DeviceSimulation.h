// The dynamics side (dT) of the CUDA backend: the state lives in device memory while DoDynamics runs;
// history mapping, the force pass and integration run as kernels compiled at run time by NVRTC from
// the same per-item code the CPU sweeps use (see docs/cuda-backend.md), on dT's own stream. Contact
// detection is the kinematics side's (DeviceKinematics: its own thread and stream, on this GPU or a
// second one), scheduled as on the CPU (runtime/DetectionSchedule.h): asynchronously beside the
// steps, or synchronously (dT waits for every detection) where the settings say so.
//
// The host SimState stays the record between calls: upload() copies it to the device after
// Initialize and after host-side edits, download() copies the evolved state back when the host needs
// it.
#pragma once

#include <memory>
#include <string>

#include "forcemodel/ModelLayout.h"
#include "kinematics/ContactDetection.h"
#include "runtime/CollaborationStats.h"
#include "runtime/FamilyRules.h"
#include "runtime/RunMonitor.h"
#include "runtime/Settings.h"
#include "runtime/SimState.h"
#include "runtime/TimingStats.h"
#include "runtime/UpdateFrequency.h"

namespace deme::cuda {

// What a device step loop found wrong (the host turns it into deme::Error).
struct DeviceFault {
    bool any = false;
    unsigned int owner = 0;  // internal id
    uint8_t flags = 0;       // OwnerStepFlag bits
    unsigned int kernelError = 0, kernelErrorItem = 0;
};

struct DeviceStepTotals {
    size_t realContacts = 0, realSphereSphere = 0;
    float maxSpeed = 0.f;
};

class DeviceSimulation {
  public:
    // Compiles (or loads from the cache) the kernels for GPU `device` (dynamics), the force model's
    // included, and starts the kinematics side on GPU `kinematicsDevice` (the same one, or a second GPU).
    DeviceSimulation(int device, int kinematicsDevice, const Settings& settings, const ModelLayout& model);
    ~DeviceSimulation();
    DeviceSimulation(const DeviceSimulation&) = delete;
    DeviceSimulation& operator=(const DeviceSimulation&) = delete;

    // Copies the whole host state (and its contact set) to the device; the next step re-detects. A
    // detection in flight (from the state being replaced) is waited for and dropped.
    void upload(const SimState& s, const BinGrid& grid, const Settings& settings, const FamilyRules& families,
                CollaborationStats& collab);
    // Advances n steps of settings.dt. Stops at the first step with a fault and reports it, or
    // where a hook of `monitor` asks.
    DeviceFault advance(unsigned long long n, const Settings& settings, FamilyRules& families, double& time,
                        unsigned long long& step, TimingStats& timing, CollaborationStats& collab,
                        DeviceStepTotals& totals, RunMonitor& monitor);
    // Copies the evolved state and contact set back into `s` (the layout upload() took).
    void download(SimState& s) const;
    // Tracker loads (AddAcc) for the coming call, or zeros.
    void uploadTrackerLoads(const SimState& s);
    // Waits for the detection in flight, if any, and installs its result if it may serve
    // (DoDynamicsThenSync).
    void finishDetection(unsigned long long step, TimingStats& timing, CollaborationStats& collab);

    unsigned int nMax() const;
    bool adaptiveUpdateFreq() const;
    double margin() const;
    double kernelCompileSeconds() const;
    bool kernelsFromCache() const;
    size_t numContacts() const;
    std::string deviceName() const;
    std::string kinematicsDeviceName() const;
    int kinematicsDevice() const;
    bool kinematicsPeerAccess() const;  // kT on a second GPU reaches dT's peer to peer

  private:
    struct Impl;
    std::unique_ptr<Impl> m;
};

}  // namespace deme::cuda
