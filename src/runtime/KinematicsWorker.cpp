#include "runtime/KinematicsWorker.h"

#include <deme/Error.h>

#include "backend/cpu/Parallel.h"
#include "runtime/WorkerFailure.h"

namespace deme {

KinematicsWorker::KinematicsWorker(const SimState& s, const BinGrid& grid, int threads) : m_grid(grid) {
    // What detection reads and never changes during a run.
    m_work.frame = s.frame;
    m_work.domainSize = s.domainSize;
    m_work.spheres = s.spheres;
    m_work.analytical = s.analytical;
    m_work.triangles.owner = s.triangles.owner;
    m_work.owners.family = s.owners.family;
    m_thread = std::thread([this, threads] { run(threads); });
}

KinematicsWorker::~KinematicsWorker() {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stop = true;
    }
    m_wake.notify_all();
    m_thread.join();
}

bool KinematicsWorker::idle() {
    std::lock_guard<std::mutex> lock(m_mutex);
    return !m_orderQueued && !m_running && !m_resultReady;
}

void KinematicsWorker::submit(const SimState& s, unsigned long long step, unsigned long long generation, double margin,
                              const uint8_t* familyMask, const float* familyExtraMargin) {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        Order& o = m_inbox;
        o.step = step;
        o.generation = generation;
        o.margin = margin;
        o.spherePos = s.cache.spherePos;
        o.analPos = s.cache.analPos;
        o.analDir = s.cache.analDir;
        o.triVert = s.cache.triVert;
        o.ownerFamily = s.owners.family;
        o.familyMask.assign(familyMask, familyMask + NUM_FAMILIES * NUM_FAMILIES);
        o.familyExtraMargin.assign(familyExtraMargin, familyExtraMargin + NUM_FAMILIES);
        m_orderQueued = true;
    }
    m_wake.notify_all();
}

void KinematicsWorker::rethrowFailure() { rethrowWorkerFailure(m_failure, "DoDynamics", "the kinematics thread"); }

bool KinematicsWorker::tryTake(DetectionResult& out) {
    std::lock_guard<std::mutex> lock(m_mutex);
    rethrowFailure();
    if (!m_resultReady) return false;
    std::swap(out, m_outbox);
    m_resultReady = false;
    return true;
}

void KinematicsWorker::waitAndTake(DetectionResult& out) {
    std::unique_lock<std::mutex> lock(m_mutex);
    m_wake.wait(lock, [this] { return m_resultReady || m_failure || (!m_orderQueued && !m_running); });
    rethrowFailure();
    if (!m_resultReady) throwError("DoDynamics", "internal: waited for a contact set that was never ordered");
    std::swap(out, m_outbox);
    m_resultReady = false;
}

void KinematicsWorker::run(int threads) {
    // This thread's own OpenMP team, sized so that it and the dynamics team share the cores.
    setCpuThreadCount(threads);
    for (;;) {
        {
            std::unique_lock<std::mutex> lock(m_mutex);
            m_wake.wait(lock, [this] { return m_stop || m_orderQueued; });
            if (m_stop) return;
            std::swap(m_current, m_inbox);
            m_orderQueued = false;
            m_running = true;
        }
        DetectionResult result;
        std::exception_ptr failure;
        try {
            m_work.cache.spherePos.swap(m_current.spherePos);
            m_work.cache.analPos.swap(m_current.analPos);
            m_work.cache.analDir.swap(m_current.analDir);
            m_work.cache.triVert.swap(m_current.triVert);
            m_work.owners.family.swap(m_current.ownerFamily);
            result.orderStep = m_current.step;
            result.generation = m_current.generation;
            result.margin = m_current.margin;
            m_detector.detect(m_work, m_grid, m_current.margin, m_current.familyMask.data(),
                              m_current.familyExtraMargin.data(), result.pairs, result.binningSeconds,
                              result.searchSeconds);
        } catch (...) {
            failure = std::current_exception();
        }
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_running = false;
            if (failure) {
                m_failure = failure;
            } else {
                std::swap(m_outbox, result);
                m_resultReady = true;
            }
        }
        m_wake.notify_all();
    }
}

}  // namespace deme
