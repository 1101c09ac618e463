#include "backend/cpu/ContactDetector.h"

#include <algorithm>
#include <chrono>

#include "parallel/Parallel.h"

namespace deme {

void BinRegistry::build(const BinGrid& grid, size_t n) {
    const size_t nBins = (size_t)grid.numBins();
    start.assign(nBins + 1, 0);
    auto forEachBin = [&](size_t i, auto&& fn) {
        for (int32_t z = lo[3 * i + 2]; z <= hi[3 * i + 2]; z++)
            for (int32_t y = lo[3 * i + 1]; y <= hi[3 * i + 1]; y++)
                for (int32_t x = lo[3 * i + 0]; x <= hi[3 * i + 0]; x++) fn((size_t)binIndex(grid, x, y, z));
    };
    for (size_t i = 0; i < n; i++) forEachBin(i, [&](size_t b) { start[b + 1]++; });
    for (size_t b = 0; b < nBins; b++) start[b + 1] += start[b];
    entries.resize(start[nBins]);
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < n; i++) forEachBin(i, [&](size_t b) { entries[fill[b]++] = (uint32_t)i; });
}

void ContactDetector::detect(const SimState& s, const BinGrid& grid, double margin, const uint8_t* familyMask,
                             const float* familyExtraMargin, DetectedContacts& out, double& binningSeconds,
                             double& searchSeconds) {
    const auto t0 = std::chrono::steady_clock::now();
    const size_t nS = s.spheres.size();
    const size_t nT = s.triangles.size();
    DetectionArgs args{grid, margin, familyExtraMargin, familyMask, {}, {}, nullptr, nullptr};

    // 1. Every geometry, enlarged by its margin, is registered in each bin its box touches.
    m_spheres.resize(nS);
#pragma omp parallel for schedule(static) if (nS > PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < nS; i++) {
        double3 lo, hi;
        sphereBox(s, args, i, lo, hi);
        storeBinBox(binBox(grid, lo, hi), i, m_spheres.lo.data(), m_spheres.hi.data());
    }
    m_spheres.build(grid, nS);
    m_triLo.resize(nT);
    m_triHi.resize(nT);
    m_triangles.resize(nT);
    for (size_t t = 0; t < nT; t++) {
        triangleBox(s, args, t, m_triLo[t], m_triHi[t]);
        storeBinBox(binBox(grid, m_triLo[t], m_triHi[t]), t, m_triangles.lo.data(), m_triangles.hi.data());
    }
    m_triangles.build(grid, nT);
    args.sphereBins = m_spheres.view();
    if (nT) args.triangleBins = m_triangles.view();
    args.triLo = m_triLo.data();
    args.triHi = m_triHi.data();
    const auto t1 = std::chrono::steady_clock::now();
    binningSeconds += std::chrono::duration<double>(t1 - t0).count();

    // 2. Pair search, per sphere, each thread over a contiguous range of spheres.
    const int T = nS > PARALLEL_MIN_ITEMS ? cpuThreadCount() : 1;
    m_threadOut.resize(T);
#pragma omp parallel num_threads(T) if (T > 1)
    {
        const int t = cpuThreadIndex();
        DetectedContacts& mine = m_threadOut[t];
        mine.geomA.clear();
        mine.geomB.clear();
        mine.type.clear();
        std::vector<bodyID_t> partners(64);
        size_t begin, end;
        threadRange(nS, t, T, begin, end);
        for (size_t a = begin; a < end; a++) {
            unsigned int n = spherePartners(s, args, (bodyID_t)a, partners.data(), (unsigned int)partners.size());
            if (n > partners.size()) {
                partners.resize(2 * (size_t)n);
                n = spherePartners(s, args, (bodyID_t)a, partners.data(), (unsigned int)partners.size());
            }
            for (unsigned int k = 0; k < n; k++) {
                mine.geomA.push_back((bodyID_t)a);
                mine.geomB.push_back(partners[k]);
                mine.type.push_back(contactTypeOf(s, partners[k]));
            }
        }
    }

    // 3. Concatenate in thread order: the result is sorted by (A, B).
    size_t total = 0;
    for (const auto& t : m_threadOut) total += t.size();
    out.geomA.resize(total);
    out.geomB.resize(total);
    out.type.resize(total);
    size_t at = 0;
    for (const auto& t : m_threadOut) {
        std::copy(t.geomA.begin(), t.geomA.end(), out.geomA.begin() + at);
        std::copy(t.geomB.begin(), t.geomB.end(), out.geomB.begin() + at);
        std::copy(t.type.begin(), t.type.end(), out.type.begin() + at);
        at += t.size();
    }
    searchSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
}

}  // namespace deme
