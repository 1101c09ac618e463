#include "backend/cpu/CpuKinematics.h"

#include <deme/Error.h>

#include "parallel/Parallel.h"
#include "runtime/RebuiltArrays.h"

namespace deme {

CpuKinematics::CpuKinematics(const SimState& live, int threads) : m_live(live), m_threads(threads) {
    const size_t keep = keepRebuiltArraysUpTo("Initialize");
    m_detector.keepBinsUpTo(keep);
    m_workDetector.keepBinsUpTo(keep);
}

CpuKinematics::~CpuKinematics() {
    m_mailbox.stop();
    if (m_thread.joinable()) m_thread.join();
}

void CpuKinematics::setGeometry(const SimState& live, const BinGrid& grid, const FamilyRules& families,
                                const Settings& settings) {
    if (!m_mailbox.idle())
        throwError("DoDynamics", "internal: the kinematics geometry changed while an order was in flight");
    m_grid = grid;
    m_familyMask.assign(families.contactMask(), families.contactMask() + NUM_FAMILIES * NUM_FAMILIES);
    m_familyExtraMargin.assign(settings.familyExtraMargin, settings.familyExtraMargin + NUM_FAMILIES);
    m_workGeometryStale = true;  // the worker's copy is made with its next order
    // The active box: which families are dormant; the cached dormant registries start afresh.
    uint8_t dormant[NUM_FAMILIES], prescribed[NUM_FAMILIES];
    families.dormantFamilies(dormant);
    families.prescribedFamilies(prescribed);
    m_detector.setFamilies(dormant, prescribed, live);
    m_workDetector.setFamilies(dormant, prescribed, live);
}

void CpuKinematics::detectNow(const DetectionOrder& order, DetectionReport& report) {
    report = DetectionReport{};
    report.order = order;
    // The live state is at the order's snapshot (its time, for a sheared cell's image offset, too).
    m_detector.detect(m_live, m_grid, order.detectionMargin(), m_familyMask.data(), m_familyExtraMargin.data(), m_taken,
                      report.binningSeconds, report.searchSeconds);
    report.numPairs = m_taken.size();
}

void CpuKinematics::submit(const DetectionOrder& order) {
    if (!m_thread.joinable()) m_thread = std::thread([this] { run(); });
    if (m_workGeometryStale) {
        // What the worker's detection reads and never changes during a run; it is idle (an order is
        // sent only then), and its thread reads m_work only while it holds one.
        m_work.frame = m_live.frame;
        m_work.domainSize = m_live.domainSize;
        m_work.spheres = m_live.spheres;
        // Where spheres are their owners the snapshot's centres are the owners' positions (below), and
        // sphere i's owner is i: the worker keeps no owners either (state/SphereLayout.h).
        m_work.spheresAreOwners = m_live.spheresAreOwners;
        m_work.analytical = m_live.analytical;
        m_work.triangles.owner = m_live.triangles.owner;
        m_workGeometryStale = false;
    }
    Order& o = m_order;
    o.order = order;
    // The spheres' centres, or where spheres are their owners the owners' compact positions
    // (state/SphereLayout.h).
    if (m_live.spheresAreOwners) {
        const size_t nS = m_live.spheres.size();
        const OwnerArrays& ow = m_live.owners;
        o.voxel.assign(ow.voxel.begin(), ow.voxel.begin() + nS);
        o.subX.assign(ow.subX.begin(), ow.subX.begin() + nS);
        o.subY.assign(ow.subY.begin(), ow.subY.begin() + nS);
        o.subZ.assign(ow.subZ.begin(), ow.subZ.begin() + nS);
    } else {
        o.spherePos = m_live.cache.spherePos;
    }
    o.analPos = m_live.cache.analPos;
    o.analDir = m_live.cache.analDir;
    o.triVert = m_live.cache.triVert;
    o.ownerFamily = m_live.owners.family;
    m_mailbox.post(o);
}

void CpuKinematics::take(Result& r, DetectionReport& report) {
    report = r.report;
    std::swap(m_taken, r.pairs);
}

bool CpuKinematics::tryTake(DetectionReport& report) {
    if (!m_mailbox.tryTake(m_result)) return false;
    take(m_result, report);
    return true;
}

void CpuKinematics::waitAndTake(DetectionReport& report) {
    m_mailbox.waitAndTake(m_result);
    take(m_result, report);
}

void CpuKinematics::run() {
    // This thread's own OpenMP team, sized so that it and the dynamics team share the cores.
    setCpuThreadCount(m_threads);
    Order order;
    Result result;
    while (m_mailbox.waitForOrder(order)) {
        try {
            if (m_work.spheresAreOwners) {
                m_work.owners.voxel.swap(order.voxel);
                m_work.owners.subX.swap(order.subX);
                m_work.owners.subY.swap(order.subY);
                m_work.owners.subZ.swap(order.subZ);
            } else {
                m_work.cache.spherePos.swap(order.spherePos);
            }
            m_work.cache.analPos.swap(order.analPos);
            m_work.cache.analDir.swap(order.analDir);
            m_work.cache.triVert.swap(order.triVert);
            m_work.owners.family.swap(order.ownerFamily);
            result.report = DetectionReport{};
            result.report.order = order.order;
            m_work.frame.periodic.shearTime = order.order.shearTime;  // the snapshot's image offset
            m_workDetector.detect(m_work, m_grid, order.order.detectionMargin(), m_familyMask.data(),
                                  m_familyExtraMargin.data(),
                                  result.pairs, result.report.binningSeconds, result.report.searchSeconds);
            result.report.numPairs = result.pairs.size();
        } catch (...) {
            m_mailbox.fail(std::current_exception());
            continue;
        }
        m_mailbox.deliver(result);
    }
}

void CpuKinematics::countHostMemory(MemoryStats& m) const {
    size_t b = m_detector.bytes() + m_taken.bytes() + vectorBytes(m_order.spherePos) + vectorBytes(m_order.analPos) +
               vectorBytes(m_order.analDir) + vectorBytes(m_order.triVert) + vectorBytes(m_order.ownerFamily) +
               vectorBytes(m_order.voxel) + vectorBytes(m_order.subX) + vectorBytes(m_order.subY) +
               vectorBytes(m_order.subZ) + m_result.pairs.bytes();
    // The worker's memory only while it works on nothing (it resizes its arrays as it goes).
    if (m_mailbox.idle()) {
        MemoryStats work;
        countStateMemory(m_work, work);
        b += work.hostTotal() + m_workDetector.bytes();
    }
    addHost(m, MemoryGroup::DETECTION, b);
}

}  // namespace deme
