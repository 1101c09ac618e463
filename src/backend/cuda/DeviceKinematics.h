// The kinematics side (kT, paper §2.1) of the CUDA backend: contact detection on its own CUDA stream,
// driven by its own host thread, on the dynamics GPU or on a second one, while the dynamics side (dT)
// keeps stepping. The GPU counterpart of runtime/KinematicsWorker: dT submits an order (a snapshot of
// what detection reads), kT bins, sorts and pair-searches, and dT takes the finished contact list.
//
// Where things live (docs/cuda-backend.md): both exchange buffers, the inbox (the snapshot) and the
// outbox (the contact list), are on dT's GPU, as in the paper: dT fills the inbox on its stream and
// reads the outbox on its stream, never touching another GPU. kT keeps on its own GPU what detection
// reads and never changes (radii, owners, analytical shapes, family rules) and its scratch (bins,
// sorted entries, per-sphere counts). On a second GPU, kT copies the snapshot to its own memory in
// one transfer (peer to peer where the GPUs allow it) because the pair search reads each position
// many times at random, and copies the contact list back in one transfer; on one GPU it reads the
// inbox and writes the outbox in place.
//
// Buffer ownership: dT writes the inbox only while kT is idle; kT writes the outbox only between
// taking an order and reporting its result, and dT reads it only after taking that result. kT
// starts reading the inbox only once dT's stream has reached the copies (an event), and reports a
// result only once its own stream has finished, so no device-side ordering between the two streams
// is needed beyond that one event.
#pragma once

#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "backend/cuda/CudaTypes.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/kernels/KernelArgs.cuh"
#include "kinematics/ContactDetection.h"
#include "runtime/FamilyRules.h"
#include "runtime/Settings.h"
#include "runtime/SimState.h"

namespace deme::cuda {

// The snapshot detection reads, on dT's GPU (written by dT).
struct KinematicsInbox {
    DeviceBuffer<double3> spherePos, triVert, analPos, analDir;
    DeviceBuffer<family_t> ownerFamily;
};

// The contact list kT found, sorted by (A, B), on dT's GPU (written by kT). dT may swap these buffers
// with its own after taking a result: kT resizes them before every write.
struct KinematicsOutbox {
    DeviceBuffer<bodyID_t> geomA, geomB;
    DeviceBuffer<uint8_t> type;
};

// What one order produced; the pairs themselves are in the outbox.
struct DeviceDetectionResult {
    unsigned long long orderStep = 0;   // dynamics step of the snapshot
    unsigned long long generation = 0;  // host edits counted by dT; older results are stale
    double margin = 0.0;
    uint32_t numPairs = 0;
    double binningSeconds = 0.0, searchSeconds = 0.0;
};

// dT's arrays an order copies the snapshot from (device memory on dT's GPU).
struct KinematicsSource {
    const DeviceBuffer<double3> *spherePos, *triVert, *analPos, *analDir;
    const DeviceBuffer<family_t>* ownerFamily;
};

class DeviceKinematics {
  public:
    // Starts kT's thread on GPU `kTDevice`, which compiles (or loads from the cache) the detection
    // kernels for that GPU and creates its stream; the exchange buffers go on `dTDevice`, which must
    // be current for the calling (dT's) thread. Throws what kT's start-up threw.
    DeviceKinematics(int kTDevice, int dTDevice);
    ~DeviceKinematics();
    DeviceKinematics(const DeviceKinematics&) = delete;
    DeviceKinematics& operator=(const DeviceKinematics&) = delete;

    // dT's thread, kT idle: what detection reads and never changes during a run (after Initialize
    // and after every host-side edit); kT copies it to its GPU before its next order. Sizes the inbox.
    void setGeometry(const SimState& s, const BinGrid& grid, const FamilyRules& families, const Settings& settings);
    // True when no order is queued or running and no result is waiting.
    bool idle();
    // dT's thread, kT idle: copies the snapshot from `src` into the inbox on `dtStream`, marks that
    // point of the stream, and hands kT the order (which starts once dT's stream is there).
    void submit(const KinematicsSource& src, Stream dtStream, unsigned long long step, unsigned long long generation,
                double margin);
    // Takes a finished result (false if none is ready). Rethrows a failure of kT.
    bool tryTake(DeviceDetectionResult& out);
    // Blocks until the order in flight has finished, then takes its result.
    void waitAndTake(DeviceDetectionResult& out);
    // The outbox, for dT after it took a result and before it submits the next order.
    KinematicsOutbox& outbox() { return m_outbox; }

    int device() const { return m_kTDevice; }
    const std::string& deviceName() const { return m_deviceName; }
    double compileSeconds() const { return m_compileSeconds; }
    bool kernelsFromCache() const { return m_fromCache; }
    // Whether kT reaches dT's GPU peer to peer (two GPUs only).
    bool peerAccess() const { return m_peerAccess; }

  private:
    struct Work;  // kT's device-side working memory, created and freed on kT's thread
    struct Geometry {
        std::vector<bodyID_t> sphereOwner, anaOwner, triOwner;
        std::vector<float> radius, anaRadius, familyExtraMargin;
        std::vector<uint8_t> anaType, anaInside, familyMask;
        BinGridView grid{};
        size_t numBins = 0;
        uint32_t numOwners = 0, numSpheres = 0, numAnalytical = 0, numTriangles = 0;
    };
    struct Order {
        unsigned long long step = 0, generation = 0;
        double margin = 0.0;
    };

    void run();
    void rethrowFailure();

    const int m_kTDevice, m_dTDevice;
    std::string m_deviceName;
    double m_compileSeconds = 0.0;
    bool m_fromCache = true, m_peerAccess = false;

    std::mutex m_mutex;
    std::condition_variable m_wake;  // kT waits for orders, dT for results and for kT's start-up
    bool m_stop = false, m_started = false, m_orderQueued = false, m_running = false, m_resultReady = false;
    bool m_geometryChanged = false;
    std::exception_ptr m_failure;
    Geometry m_geometry;  // written by dT only while kT is idle
    Order m_order;
    DeviceDetectionResult m_result;

    // Exchange buffers, on dT's GPU.
    KinematicsInbox m_inbox;
    KinematicsOutbox m_outbox;
    void* m_submitted = nullptr;  // a cudaEvent_t on dT's GPU: dT's stream has filled the inbox

    std::thread m_thread;  // last member: starts after everything above exists
};

}  // namespace deme::cuda
