#include "kinematics/ContactDetection.h"

#include <algorithm>
#include <cmath>

#include "backend/cpu/Parallel.h"
#include "physics/ContactGeometry.h"
#include "physics/RigidBody.h"

namespace deme {

BinGrid makeBinGrid(const SimState& s, double requestedSize) {
    BinGrid g;
    g.origin = s.frame.origin;
    double size = requestedSize;
    if (size <= 0.0) {
        float rmax = 0.f;
        for (float r : s.spheres.radius) rmax = std::max(rmax, r);
        size = 2.0 * rmax;
        const double volume = s.domainSize.x * s.domainSize.y * s.domainSize.z;
        const double nTarget = 8.0 * (double)std::max<size_t>(s.spheres.size(), 1);
        size = std::max(size, std::cbrt(volume / nTarget));
    }
    // Never more bins along an axis than positions can distinguish.
    size = std::max(size, std::max({s.domainSize.x, s.domainSize.y, s.domainSize.z}) / 1e6);
    g.size = size;
    g.nx = std::max<int64_t>(1, (int64_t)std::ceil(s.domainSize.x / size));
    g.ny = std::max<int64_t>(1, (int64_t)std::ceil(s.domainSize.y / size));
    g.nz = std::max<int64_t>(1, (int64_t)std::ceil(s.domainSize.z / size));
    return g;
}

namespace {

inline int32_t binCoord(double x, double origin, double size, int64_t n) {
    const double f = std::floor((x - origin) / size);
    if (!(f > 0.0)) return 0;  // also maps NaN to 0; NaN positions are caught by the integrator
    if (f >= (double)(n - 1)) return (int32_t)(n - 1);
    return (int32_t)f;
}

}  // namespace

void ContactDetector::detect(const SimState& s, const BinGrid& grid, double margin, const uint8_t* familyMask,
                             DetectedContacts& out) {
    const size_t nS = s.spheres.size();
    const size_t nA = s.analytical.size();
    const OwnerArrays& ow = s.owners;

    // 1. The enlarged boxes' bin ranges.
    const std::vector<double3>& spherePos = s.cache.spherePos;
    m_binLo.resize(3 * nS);
    m_binHi.resize(3 * nS);
#pragma omp parallel for schedule(static) if (nS > PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < nS; i++) {
        const double3 p = spherePos[i];
        const double e = (double)s.spheres.radius[i] + margin;
        m_binLo[3 * i + 0] = binCoord(p.x - e, grid.origin.x, grid.size, grid.nx);
        m_binLo[3 * i + 1] = binCoord(p.y - e, grid.origin.y, grid.size, grid.ny);
        m_binLo[3 * i + 2] = binCoord(p.z - e, grid.origin.z, grid.size, grid.nz);
        m_binHi[3 * i + 0] = binCoord(p.x + e, grid.origin.x, grid.size, grid.nx);
        m_binHi[3 * i + 1] = binCoord(p.y + e, grid.origin.y, grid.size, grid.ny);
        m_binHi[3 * i + 2] = binCoord(p.z + e, grid.origin.z, grid.size, grid.nz);
    }

    // 2. Register each sphere in every bin its enlarged box touches (counting sort by bin, stable
    // in sphere order, so each bin lists its spheres in increasing id).
    const size_t nBins = grid.numBins();
    m_binStart.assign(nBins + 1, 0);
    auto forEachBin = [&](size_t i, auto&& fn) {
        for (int32_t z = m_binLo[3 * i + 2]; z <= m_binHi[3 * i + 2]; z++)
            for (int32_t y = m_binLo[3 * i + 1]; y <= m_binHi[3 * i + 1]; y++)
                for (int32_t x = m_binLo[3 * i + 0]; x <= m_binHi[3 * i + 0]; x++)
                    fn((size_t)x + (size_t)grid.nx * ((size_t)y + (size_t)grid.ny * (size_t)z));
    };
    for (size_t i = 0; i < nS; i++) forEachBin(i, [&](size_t b) { m_binStart[b + 1]++; });
    for (size_t b = 0; b < nBins; b++) m_binStart[b + 1] += m_binStart[b];
    m_binEntries.resize(m_binStart[nBins]);
    {
        std::vector<uint32_t> fill(m_binStart.begin(), m_binStart.end() - 1);
        for (size_t i = 0; i < nS; i++) forEachBin(i, [&](size_t b) { m_binEntries[fill[b]++] = (uint32_t)i; });
    }

    // 3. Pair search, per sphere A: partners B > A in A's bins, each pair reported only from the bin
    // that holds the lower corner of the two enlarged boxes' intersection, so exactly once.
    const int T = nS > PARALLEL_MIN_ITEMS ? cpuThreadCount() : 1;
    m_threadOut.resize(T);
    const double twoMargin = 2.0 * margin;
#pragma omp parallel num_threads(T) if (T > 1)
    {
        const int t = cpuThreadIndex();
        DetectedContacts& mine = m_threadOut[t];
        mine.geomA.clear();
        mine.geomB.clear();
        mine.type.clear();
        std::vector<bodyID_t> partners;
        size_t begin, end;
        threadRange(nS, t, T, begin, end);
        for (size_t a = begin; a < end; a++) {
            const double3 pA = spherePos[a];
            const double rA = s.spheres.radius[a];
            const double eA = rA + margin;
            const bodyID_t oA = s.spheres.owner[a];
            const uint8_t* maskRow = familyMask + (size_t)ow.family[oA] * NUM_FAMILIES;
            partners.clear();
            for (int32_t z = m_binLo[3 * a + 2]; z <= m_binHi[3 * a + 2]; z++)
                for (int32_t y = m_binLo[3 * a + 1]; y <= m_binHi[3 * a + 1]; y++)
                    for (int32_t x = m_binLo[3 * a + 0]; x <= m_binHi[3 * a + 0]; x++) {
                        const size_t bin = (size_t)x + (size_t)grid.nx * ((size_t)y + (size_t)grid.ny * (size_t)z);
                        const uint32_t* first = m_binEntries.data() + m_binStart[bin];
                        const uint32_t* last = m_binEntries.data() + m_binStart[bin + 1];
                        for (const uint32_t* it = std::upper_bound(first, last, (uint32_t)a); it != last; ++it) {
                            const uint32_t b = *it;
                            const bodyID_t oB = s.spheres.owner[b];
                            if (oB == oA || !maskRow[ow.family[oB]]) continue;
                            const double3 pB = spherePos[b];
                            const double eB = (double)s.spheres.radius[b] + margin;
                            const double reach = eA + eB;
                            const double3 d = pA - pB;
                            if (fabs(d.x) > reach || fabs(d.y) > reach || fabs(d.z) > reach) continue;
                            if (binCoord(std::max(pA.x - eA, pB.x - eB), grid.origin.x, grid.size, grid.nx) != x ||
                                binCoord(std::max(pA.y - eA, pB.y - eB), grid.origin.y, grid.size, grid.ny) != y ||
                                binCoord(std::max(pA.z - eA, pB.z - eB), grid.origin.z, grid.size, grid.nz) != z)
                                continue;
                            if (dot(d, d) >= reach * reach) continue;
                            partners.push_back(b);
                        }
                    }
            std::sort(partners.begin(), partners.end());
            for (bodyID_t b : partners) {
                mine.geomA.push_back((bodyID_t)a);
                mine.geomB.push_back(b);
                mine.type.push_back(SPHERE_SPHERE);
            }
            for (size_t k = 0; k < nA; k++) {
                const bodyID_t oB = s.analytical.owner[k];
                if (!maskRow[ow.family[oB]]) continue;
                const double dist = s.analytical.type[k] == ANAL_PLANE
                                        ? planeSignedDistance(pA, s.cache.analPos[k], s.cache.analDir[k])
                                        : cylinderSignedDistance(pA, s.cache.analPos[k], s.cache.analDir[k],
                                                                 s.analytical.radius[k], s.analytical.inside[k] != 0);
                if (dist - rA < twoMargin) {
                    mine.geomA.push_back((bodyID_t)a);
                    mine.geomB.push_back((bodyID_t)(nS + k));
                    mine.type.push_back(SPHERE_ANALYTICAL);
                }
            }
        }
    }

    // 4. Concatenate in thread order: the result is sorted by (A, B).
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
}

}  // namespace deme
