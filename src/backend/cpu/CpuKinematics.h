// The kinematics side (kT, paper §2.1) on the CPU: contact detection on the dynamics thread
// (detectNow, with the dynamics' OpenMP team) or on a thread of its own beside the steps, fed
// through the worker mailbox (runtime/WorkerMailbox.h) with a snapshot of the geometry; both run the
// same ContactDetector.
//
// Buffers belong to their consumer: the order (snapshot) is kT's from the moment dT posts it, the
// result dT's from the moment it takes it. Neither side touches the other's working memory: kT
// detects on its own copy of the geometry.
#pragma once

#include <memory>
#include <thread>

#include "backend/cpu/ContactDetector.h"
#include "runtime/Backends.h"
#include "runtime/WorkerMailbox.h"

namespace deme {

class CpuKinematics : public KinematicsBackend {
  public:
    // `live` is the state the steps run on (snapshots are taken from it); the thread's detection
    // loops use `threads` OpenMP threads.
    CpuKinematics(const SimState& live, int threads);
    ~CpuKinematics() override;
    CpuKinematics(const CpuKinematics&) = delete;
    CpuKinematics& operator=(const CpuKinematics&) = delete;

    void setGeometry(const SimState& s, const BinGrid& grid, const FamilyRules& families,
                     const Settings& settings) override;
    void submit(const DetectionOrder& order) override;
    bool tryTake(DetectionReport& report) override;
    void waitAndTake(DetectionReport& report) override;
    void detectNow(const DetectionOrder& order, DetectionReport& report) override;
    bool sharesDynamicsDevice() const override { return false; }

    // The pairs of the result taken last (sorted by key), for installation.
    DetectedContacts& takenPairs() { return m_taken; }
    void countHostMemory(MemoryStats& m) const override;

  private:
    // An order: the snapshot of the geometry that moves, and the parameters.
    struct Order {
        DetectionOrder order;
        std::vector<double3> spherePos, analPos, analDir, triVert;
        std::vector<family_t> ownerFamily;
        // Where spheres are their owners, their owners' compact positions instead of spherePos
        // (state/OwnerCentre.h: the worker decodes them as the steps do).
        std::vector<voxelID_t> voxel;
        std::vector<subVoxelPos_t> subX, subY, subZ;
    };
    struct Result {
        DetectionReport report;
        DetectedContacts pairs;
    };
    using Mailbox = WorkerMailbox<Order, Result>;

    void run();
    void take(Result& r, DetectionReport& report);

    const SimState& m_live;
    const int m_threads;
    BinGrid m_grid{};
    std::vector<uint8_t> m_familyMask;
    std::vector<float> m_familyExtraMargin;
    ContactDetector m_detector;  // detections on the dynamics thread
    DetectedContacts m_taken;
    Order m_order;    // dT's, between orders (keeps its capacity)
    Result m_result;  // dT's, between takes

    // The worker thread, started with the first order; its working memory (its copy of the static
    // geometry made with the first order after setGeometry, so synchronous runs keep none).
    Mailbox m_mailbox{"the kinematics thread"};
    SimState m_work;
    bool m_workGeometryStale = true;
    ContactDetector m_workDetector;
    std::thread m_thread;
};

}  // namespace deme
