// The kinematics side (kT, paper §2.1) of the CUDA backend: contact detection on its own CUDA stream,
// driven by its own host thread through the worker mailbox (runtime/WorkerMailbox.h), on the
// dynamics GPU or on a second one, while the dynamics side (dT) keeps stepping. dT submits an order
// (a snapshot of what detection reads), kT bins, sorts and pair-searches with the rules of
// kinematics/DetectionRules.h, and dT takes the finished contact list.
//
// Where things live (docs/cuda-backend.md): both exchange buffers, the inbox (the snapshot) and the
// outbox (the contact list), are on dT's GPU, as in the paper: dT fills the inbox on its stream and
// reads the outbox on its stream, never touching another GPU. kT keeps on its own GPU what detection
// reads and never changes (radii, owners, analytical shapes, family rules) and its scratch (bins,
// sorted entries, per-sphere counts). On a second GPU, kT copies the snapshot to its own memory in
// one transfer (peer to peer where the GPUs allow it) because the pair search reads each position
// many times at random, and copies the contact list back in one transfer; on one GPU it reads the
// inbox and writes the outbox in place. A synchronous detection on one GPU (detectNow) takes no
// snapshot: dT waits for it, so its state stands still, and kT reads it where it is. A run that
// only detects so never holds an inbox, and lets go of large scratch after each detection
// (docs/memory.md).
//
// Buffer ownership: dT writes the inbox only while kT is idle; kT writes the outbox only between
// taking an order and reporting its result, and dT reads it only after taking that result. kT
// starts reading the inbox only once dT's stream has reached the copies (an event), and reports a
// result only once its own stream has finished, so no device-side ordering between the two streams
// is needed beyond that one event.
#pragma once

#include <atomic>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "backend/cuda/CudaTypes.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/DevicePairA.h"
#include "backend/cuda/DeviceDormantRegistry.h"
#include "backend/cuda/DeviceState.h"
#include "runtime/Backends.h"
#include "runtime/WorkerMailbox.h"

namespace deme::cuda {

// The snapshot detection reads, on dT's GPU (written by dT): the spheres' centres, or where spheres
// are their owners the owners' compact positions (the detection decodes them as the steps do,
// state/OwnerCentre.h), and what else moves.
struct KinematicsInbox {
    DeviceBuffer<double3> spherePos, triVert, analPos, analDir;
    DeviceBuffer<family_t> ownerFamily;
    DeviceBuffer<voxelID_t> voxel;
    DeviceBuffer<subVoxelPos_t> subX, subY, subZ;

    void setGroup(MemoryGroup g);
    size_t bytes() const;
    void release();
    // Sized for a snapshot of these counts; the form the layout does not read is let go.
    void resize(bool spheresAreOwners, size_t numOwners, size_t numSpheres, size_t numAnalytical, size_t numTriangles);
    // A copy of `src`'s snapshot, as sized (on `stream`; src on another GPU).
    void copyFrom(const KinematicsInbox& src, Stream stream);

  private:
    // f(buffer of this, buffer of others...) for each buffer, the same one of each inbox.
    template <class F, class... I>
    void forEachBuffer(F&& f, I&... others) {
        f(spherePos, others.spherePos...);
        f(triVert, others.triVert...);
        f(analPos, others.analPos...);
        f(analDir, others.analDir...);
        f(ownerFamily, others.ownerFamily...);
        f(voxel, others.voxel...);
        f(subX, others.subX...);
        f(subY, others.subY...);
        f(subZ, others.subZ...);
    }
};

// The contact list kT found, sorted by (A, B), on dT's GPU (written by kT). dT may swap these buffers
// with its own after taking a result: kT resizes them before every write.
struct KinematicsOutbox {
    DevicePairA pairA;             // A compact (state/CompactPairA.h)
    DeviceBuffer<bodyID_t> geomB;  // (a pair's type follows from B: state/ContactTypeOf.h)
};

class CudaKinematics : public KinematicsBackend {
  public:
    // Starts kT's thread on GPU `kTDevice`, which compiles (or loads from the cache) the detection
    // kernels for that GPU and creates its stream; the exchange buffers go on `dTDevice`, which must
    // be current for the calling (dT's) thread. Orders snapshot `source` on `dtStream`. Throws what
    // kT's start-up threw.
    CudaKinematics(int kTDevice, int dTDevice, const DeviceState& source, Stream dtStream);
    ~CudaKinematics() override;
    CudaKinematics(const CudaKinematics&) = delete;
    CudaKinematics& operator=(const CudaKinematics&) = delete;

    void setGeometry(const SimState& s, const BinGrid& grid, const FamilyRules& families,
                     const Settings& settings) override;
    void submit(const DetectionOrder& order) override;
    bool tryTake(DetectionReport& report) override;
    void waitAndTake(DetectionReport& report) override;
    void detectNow(const DetectionOrder& order, DetectionReport& report) override;
    bool sharesDynamicsDevice() const override { return m_kTDevice == m_dTDevice; }
    bool detectsInPlace() const override { return m_kTDevice == m_dTDevice; }
    bool mayBinSpheresByCentre(size_t spheres) const override;

    // The outbox, for dT after it took a result and before it submits the next order.
    KinematicsOutbox& outbox() { return m_outbox; }

    int device() const { return m_kTDevice; }
    const std::string& deviceName() const { return m_deviceName; }
    double compileSeconds() const { return m_compileSeconds; }
    bool kernelsFromCache() const { return m_fromCache; }
    // Whether kT reaches dT's GPU peer to peer (two GPUs only).
    bool peerAccess() const { return m_peerAccess; }
    // How often the dormant registry was built (DeviceDormantRegistry), as of the last result taken.
    size_t dormantRegistryRebuilds() const { return m_dormantRebuilds.load(); }

  private:
    struct Work;  // kT's device-side working memory, created and freed on kT's thread
    struct Geometry {
        std::vector<bodyID_t> sphereOwner, anaOwner, triOwner;
        std::vector<float> radius, anaRadius, familyExtraMargin;
        double minRadius = 0.0, maxRadius = 0.0;  // the smallest and largest sphere's radius
        // The spheres searched by several threads each, of radius wideRadius or more (DetectionLanes.h).
        std::vector<bodyID_t> wideSpheres;
        float wideRadius = 0.f;
        std::vector<uint8_t> anaType, anaInside, familyMask;
        BinGrid grid{};
        DomainFrame frame{};  // its periodic box: detection compares geometries through their nearest images
        uint32_t numOwners = 0, numSpheres = 0, numAnalytical = 0, numTriangles = 0;
        bool spheresAreOwners = false;  // the snapshot's centres are the owners' (state/SphereLayout.h)
        DormantFamilies dormant;  // the active box's families (DeviceDormantRegistry)
    };
    struct Order {
        DetectionOrder order;
        bool geometryChanged = false;  // kT copies m_geometry to its GPU first
        // A synchronous detection on dT's GPU: kT reads dT's state (m_source) instead of the inbox,
        // and lets go of its scratch at the end where that is large (m_keepScratchUpTo).
        bool inPlace = false;
    };
    using Mailbox = WorkerMailbox<Order, DetectionReport>;

    void run();
    // Sends an order: with the snapshot copied into the inbox, or (inPlace) none.
    void post(const DetectionOrder& order, bool inPlace);

    const int m_kTDevice, m_dTDevice;
    const DeviceState& m_source;
    const Stream m_dtStream;
    std::string m_deviceName;
    double m_compileSeconds = 0.0;
    bool m_fromCache = true, m_peerAccess = false;
    std::atomic<size_t> m_dormantRebuilds{0};

    Mailbox m_mailbox{"the GPU kinematics thread"};
    // Start-up: kT reports once it is ready (or why it could not start).
    std::mutex m_startMutex;
    std::condition_variable m_startWake;
    bool m_started = false;
    std::exception_ptr m_startFailure;

    Geometry m_geometry;  // written by dT only while kT is idle
    bool m_geometryChanged = false;
    // Detection's arrays rebuilt each time (the inbox, the bins, the per-sphere counts) are kept
    // between synchronous detections up to this many bytes (keepRebuiltArraysUpTo).
    size_t m_keepScratchUpTo = 0;

    // Exchange buffers, on dT's GPU.
    KinematicsInbox m_inbox;
    KinematicsOutbox m_outbox;
    void* m_submitted = nullptr;  // a cudaEvent_t on dT's GPU: dT's stream has filled the inbox

    std::thread m_thread;  // last member: starts after everything above exists
};

}  // namespace deme::cuda
