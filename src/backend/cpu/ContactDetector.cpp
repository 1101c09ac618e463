#include "backend/cpu/ContactDetector.h"

#include <algorithm>
#include <chrono>

#include "parallel/Parallel.h"
#include "runtime/IndexLimits.h"
#include "runtime/MemoryEstimate.h"

namespace deme {

void ContactDetector::detect(const SimState& s, const BinGrid& sceneGrid, double margin, const uint8_t* familyMask,
                             const float* familyExtraMargin, DetectedContacts& out, double& binningSeconds,
                             double& searchSeconds) {
    const auto t0 = std::chrono::steady_clock::now();
    const BinGrid grid = withShearOffset(sceneGrid, s.frame.periodic);
    const size_t nS = s.spheres.size();
    const size_t nT = s.triangles.size();
    DetectionArgs args{grid, margin, familyExtraMargin, familyMask, {}, {}, nullptr, nullptr,
                       sharedExtraMarginOf(familyExtraMargin)};
    // The active box: with dormant spheres cached, only the moving ones are binned and searched.
    const bool dormant = m_dormant.prepare(s, grid, familyMask, familyExtraMargin);
    const bodyID_t* searched = dormant ? m_dormant.moving().data() : nullptr;  // null: every sphere
    const size_t nSearched = dormant ? m_dormant.moving().size() : nS;
    auto sphereAt = [searched](size_t k) { return searched ? (size_t)searched[k] : k; };
    // Spheres by centre where none reaches far beyond a bin (kinematics/DetectionRules.h).
    float maxRadius = 0.f;
#pragma omp parallel for reduction(max : maxRadius) if (nSearched > PARALLEL_MIN_ITEMS)
    for (size_t k = 0; k < nSearched; k++) maxRadius = std::max(maxRadius, s.spheres.radius[sphereAt(k)]);
    args.centreReach = centreReachFor(grid, margin, familyExtraMargin, (double)maxRadius);

    // 1. Every geometry, enlarged by its margin, is registered in each bin its box touches (spheres
    // by their centres where args.centreReach says so).
    m_spheres.build(grid, searched, nSearched, [&](size_t i) { return sphereBinBox(s, args, i); });
    m_triLo.resize(nT);
    m_triHi.resize(nT);
    for (size_t t = 0; t < nT; t++) triangleBox(s, args, t, m_triLo[t], m_triHi[t]);
    args.triLo = m_triLo.data();
    args.triHi = m_triHi.data();
    m_triangles.build(grid, nullptr, nT, [&](size_t t) { return triangleBinBox(args, t); });
    args.sphereBins = m_spheres.view();
    if (nT) args.triangleBins = m_triangles.view();
    const DormantBinsView dormantBins = m_dormant.view();
    const auto t1 = std::chrono::steady_clock::now();
    binningSeconds += std::chrono::duration<double>(t1 - t0).count();

    // 2. Pair search, per sphere, each thread over a contiguous range of spheres; a moving sphere's
    // dormant partners after its own (such pairs are keyed by the lower id, sorted below).
    const int T = nSearched > PARALLEL_MIN_ITEMS ? cpuThreadCount() : 1;
    m_threadOut.resize(T);
    // Room for each thread's share of as many pairs as last time, and a little more: grown by
    // doubling instead, the lists would hold up to twice the pairs' bytes while the copies below
    // are made. The first detection takes the memory estimate's pairs per sphere (a dense
    // packing's): room never written takes no memory (runtime/AllocatorPolicy.h maps it).
    const size_t last = m_lastPairs ? m_lastPairs : (size_t)(ESTIMATED_PAIRS_PER_SPHERE * (double)nSearched);
    const bool runs = !dormant && last >= nSearched;  // A as runs where they are the smaller
#pragma omp parallel num_threads(T) if (T > 1)
    {
        const int t = cpuThreadIndex();
        ThreadPairs& mine = m_threadOut[t];
        size_t begin, end;
        threadRange(nSearched, t, T, begin, end);
        const size_t expected = last / (size_t)T + last / (size_t)T / 16 + 64;
        mine.firstSearched = begin;
        mine.geomB.reserve(expected);
        if (runs)
            mine.runs.reserve(end - begin);
        else
            mine.geomA.reserve(expected);
        std::vector<bodyID_t> partners(64);
        for (size_t k = begin; k < end; k++) {
            const bodyID_t a = (bodyID_t)sphereAt(k);
            unsigned int n = spherePartners(s, args, a, partners.data(), (unsigned int)partners.size());
            if (n > partners.size()) {
                partners.resize(2 * (size_t)n);
                n = spherePartners(s, args, a, partners.data(), (unsigned int)partners.size());
            }
            mine.geomB.insert(mine.geomB.end(), partners.begin(), partners.begin() + n);
            if (runs) {
                mine.runs.push_back(n);
                continue;
            }
            mine.geomA.insert(mine.geomA.end(), n, a);
            if (!dormant) continue;
            n = dormantPartners(s, args, dormantBins, a, partners.data(), (unsigned int)partners.size());
            if (n > partners.size()) {
                partners.resize(2 * (size_t)n);
                n = dormantPartners(s, args, dormantBins, a, partners.data(), (unsigned int)partners.size());
            }
            for (unsigned int j = 0; j < n; j++) {
                mine.geomA.push_back(std::min(a, partners[j]));
                mine.geomB.push_back(std::max(a, partners[j]));
            }
        }
    }

    // The bins are rebuilt by every detection: large ones are let go until the next instead of held
    // through the steps between (the early mixer's 58 B per sphere), and before the pairs are
    // copied below (a detection's peak). Allocating them again makes a detection's binning slower
    // by a third or a half (its pages are new), about 1 % of the steps of a packed bed detected
    // every 85 steps; so small ones, whose bytes do not matter, stay.
    const size_t binBytes = m_spheres.bytes() + m_triangles.bytes() + vectorBytes(m_triLo) + vectorBytes(m_triHi);
    if (binBytes > m_keepBinsUpTo) {
        m_spheres.release();
        m_triangles.release();
        releaseVector(m_triLo);
        releaseVector(m_triHi);
    }

    // 3. Concatenate in thread order: the result is sorted by (A, B), or is sorted so below. One
    // field at a time, each thread's list of it let go once made, and A made only once B is, so
    // that the pairs are held twice over one field's bytes at most (8 B per pair, not 12: made
    // together, the two fields and the threads' B were a later detection's peak, docs/memory.md).
    size_t total = 0;
    for (const ThreadPairs& t : m_threadOut) total += t.size();
    requireIndexable(total, "contact pairs", FEWER_PAIRS_REMEDY, "DoDynamics");
    out.geomB.resize(total);
    size_t at = 0;
    for (ThreadPairs& t : m_threadOut) {
        std::copy(t.geomB.begin(), t.geomB.end(), out.geomB.begin() + at);
        at += t.size();
        releaseVector(t.geomB);
    }
    out.geomA.resize(total);
    at = 0;
    for (ThreadPairs& t : m_threadOut) {
        if (!runs) {
            std::copy(t.geomA.begin(), t.geomA.end(), out.geomA.begin() + at);
            at += t.geomA.size();
        } else {
            for (size_t k = 0; k < t.runs.size(); k++) {
                std::fill_n(out.geomA.begin() + at, t.runs[k], (bodyID_t)(t.firstSearched + k));
                at += t.runs[k];
            }
        }
        releaseVector(t.geomA);
        releaseVector(t.runs);
    }
    releaseVector(m_threadOut);  // each thread's (now empty) lists: only while a detection runs
    m_lastPairs = total;
    if (dormant) sortPairs(out);
    searchSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
}

// Pairs into (A, B) order. The keys live only while they sort (held between detections they were
// 8 B per pair).
void ContactDetector::sortPairs(DetectedContacts& out) {
    const size_t n = out.size();
    std::vector<uint64_t> keys(n);
    for (size_t i = 0; i < n; i++) keys[i] = ((uint64_t)out.geomA[i] << 32) | (uint64_t)out.geomB[i];
    std::sort(keys.begin(), keys.end());
    for (size_t i = 0; i < n; i++) {
        out.geomA[i] = (bodyID_t)(keys[i] >> 32);
        out.geomB[i] = (bodyID_t)(keys[i] & 0xFFFFFFFFu);
    }
}

}  // namespace deme
