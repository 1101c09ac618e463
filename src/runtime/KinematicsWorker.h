// The kinematics thread (kT, paper §2.1): detects contacts from a work order (a snapshot of the
// geometry) while the dynamics thread (dT) keeps stepping, and hands back the new contact set.
//
// Buffers belong to their consumer: the work-order inbox is kT's, written by dT only while kT is
// idle; the result outbox is dT's, written by kT only while dT is not holding it. Neither side
// touches the other's working memory: kT detects on its own copy of the geometry.
#pragma once

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "kinematics/ContactDetection.h"
#include "runtime/SimState.h"

namespace deme {

struct DetectionResult {
    unsigned long long orderStep = 0;   // dynamics step of the snapshot
    unsigned long long generation = 0;  // host edits since the start; older results are stale
    double margin = 0.0;
    DetectedContacts pairs;
    double binningSeconds = 0.0, searchSeconds = 0.0;
};

class KinematicsWorker {
  public:
    // Copies the static geometry of `s` (radii, owners, analytical shapes) and starts the thread,
    // whose detection loops use `threads` OpenMP threads.
    KinematicsWorker(const SimState& s, const BinGrid& grid, int threads);
    ~KinematicsWorker();
    KinematicsWorker(const KinematicsWorker&) = delete;
    KinematicsWorker& operator=(const KinematicsWorker&) = delete;

    // True when no order is queued or running and no result is waiting.
    bool idle();
    // Sends a work order: the current geometry of `s`. Call only when idle().
    void submit(const SimState& s, unsigned long long step, unsigned long long generation, double margin,
                const uint8_t* familyMask, const float* familyExtraMargin);
    // Moves a finished result into `out` (false if none is ready). Rethrows a failure of kT.
    bool tryTake(DetectionResult& out);
    // Blocks until the order in flight has finished, then moves its result into `out`.
    void waitAndTake(DetectionResult& out);

  private:
    void run(int threads);
    void rethrowFailure();

    std::mutex m_mutex;
    std::condition_variable m_wake;  // kT waits for orders, dT for results
    bool m_stop = false, m_orderQueued = false, m_running = false, m_resultReady = false;
    std::exception_ptr m_failure;

    // Inbox (kT's): the order's dynamic geometry and parameters.
    struct Order {
        unsigned long long step = 0, generation = 0;
        double margin = 0.0;
        std::vector<double3> spherePos, analPos, analDir, triVert;
        std::vector<family_t> ownerFamily;
        std::vector<uint8_t> familyMask;
        std::vector<float> familyExtraMargin;
    } m_inbox;
    DetectionResult m_outbox;  // dT's

    // kT's working memory.
    SimState m_work;
    Order m_current;
    BinGrid m_grid;
    ContactDetector m_detector;
    std::thread m_thread;  // last member: starts after everything above exists
};

}  // namespace deme
