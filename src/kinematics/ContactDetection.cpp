#include "kinematics/ContactDetection.h"

#include <algorithm>
#include <chrono>
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

// Counting sort of items into the bins their boxes [lo, hi] touch; stable in item order, so each
// bin lists its items in increasing id.
void BinRegistry::build(const BinGrid& grid, size_t n) {
    const size_t nBins = grid.numBins();
    start.assign(nBins + 1, 0);
    auto forEachBin = [&](size_t i, auto&& fn) {
        for (int32_t z = lo[3 * i + 2]; z <= hi[3 * i + 2]; z++)
            for (int32_t y = lo[3 * i + 1]; y <= hi[3 * i + 1]; y++)
                for (int32_t x = lo[3 * i + 0]; x <= hi[3 * i + 0]; x++)
                    fn((size_t)x + (size_t)grid.nx * ((size_t)y + (size_t)grid.ny * (size_t)z));
    };
    for (size_t i = 0; i < n; i++) forEachBin(i, [&](size_t b) { start[b + 1]++; });
    for (size_t b = 0; b < nBins; b++) start[b + 1] += start[b];
    entries.resize(start[nBins]);
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < n; i++) forEachBin(i, [&](size_t b) { entries[fill[b]++] = (uint32_t)i; });
}

void BinRegistry::setBox(const BinGrid& g, size_t i, const double3& boxLo, const double3& boxHi) {
    lo[3 * i + 0] = binCoord(boxLo.x, g.origin.x, g.size, g.nx);
    lo[3 * i + 1] = binCoord(boxLo.y, g.origin.y, g.size, g.ny);
    lo[3 * i + 2] = binCoord(boxLo.z, g.origin.z, g.size, g.nz);
    hi[3 * i + 0] = binCoord(boxHi.x, g.origin.x, g.size, g.nx);
    hi[3 * i + 1] = binCoord(boxHi.y, g.origin.y, g.size, g.ny);
    hi[3 * i + 2] = binCoord(boxHi.z, g.origin.z, g.size, g.nz);
}

void ContactDetector::detect(const SimState& s, const BinGrid& grid, double margin, const uint8_t* familyMask,
                             const float* familyExtraMargin, DetectedContacts& out, double& binningSeconds,
                             double& searchSeconds) {
    const auto t0 = std::chrono::steady_clock::now();
    auto marginOf = [&](bodyID_t owner) { return margin + (double)familyExtraMargin[s.owners.family[owner]]; };
    const size_t nS = s.spheres.size();
    const size_t nA = s.analytical.size();
    const size_t nT = s.triangles.size();
    const OwnerArrays& ow = s.owners;
    const KinematicCache& k = s.cache;

    // 1. Every geometry, enlarged by the margin, is registered in each bin its box touches.
    m_spheres.resize(nS);
#pragma omp parallel for schedule(static) if (nS > PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < nS; i++) {
        const double e = (double)s.spheres.radius[i] + marginOf(s.spheres.owner[i]);
        const double3 p = k.spherePos[i];
        m_spheres.setBox(grid, i, make_double3(p.x - e, p.y - e, p.z - e), make_double3(p.x + e, p.y + e, p.z + e));
    }
    m_spheres.build(grid, nS);
    m_triLo.resize(nT);
    m_triHi.resize(nT);
    m_triangles.resize(nT);
    for (size_t t = 0; t < nT; t++) {
        const double3* v = &k.triVert[3 * t];
        const double em = marginOf(s.triangles.owner[t]);
        m_triLo[t] = make_double3(std::min({v[0].x, v[1].x, v[2].x}) - em, std::min({v[0].y, v[1].y, v[2].y}) - em,
                                  std::min({v[0].z, v[1].z, v[2].z}) - em);
        m_triHi[t] = make_double3(std::max({v[0].x, v[1].x, v[2].x}) + em, std::max({v[0].y, v[1].y, v[2].y}) + em,
                                  std::max({v[0].z, v[1].z, v[2].z}) + em);
        m_triangles.setBox(grid, t, m_triLo[t], m_triHi[t]);
    }
    m_triangles.build(grid, nT);
    const auto t1 = std::chrono::steady_clock::now();
    binningSeconds += std::chrono::duration<double>(t1 - t0).count();

    // 2. Pair search, per sphere A: partners in A's bins, each pair reported only from the bin that
    // holds the lower corner of the two enlarged boxes' intersection, so exactly once.
    const int T = nS > PARALLEL_MIN_ITEMS ? cpuThreadCount() : 1;
    m_threadOut.resize(T);
    const bodyID_t triBase = s.triangleIdBase();
#pragma omp parallel num_threads(T) if (T > 1)
    {
        const int t = cpuThreadIndex();
        DetectedContacts& mine = m_threadOut[t];
        mine.geomA.clear();
        mine.geomB.clear();
        mine.type.clear();
        std::vector<bodyID_t> partners, triPartners;
        size_t begin, end;
        threadRange(nS, t, T, begin, end);
        for (size_t a = begin; a < end; a++) {
            const double3 pA = k.spherePos[a];
            const double rA = s.spheres.radius[a];
            const double eA = rA + marginOf(s.spheres.owner[a]);
            const double3 loA = make_double3(pA.x - eA, pA.y - eA, pA.z - eA);
            const bodyID_t oA = s.spheres.owner[a];
            const uint8_t* maskRow = familyMask + (size_t)ow.family[oA] * NUM_FAMILIES;
            // True if this bin holds the lower corner of the intersection of A's box and [lo, ...].
            auto ownsPair = [&](const double3& lo, int32_t x, int32_t y, int32_t z) {
                return binCoord(std::max(loA.x, lo.x), grid.origin.x, grid.size, grid.nx) == x &&
                       binCoord(std::max(loA.y, lo.y), grid.origin.y, grid.size, grid.ny) == y &&
                       binCoord(std::max(loA.z, lo.z), grid.origin.z, grid.size, grid.nz) == z;
            };
            partners.clear();
            triPartners.clear();
            for (int32_t z = m_spheres.lo[3 * a + 2]; z <= m_spheres.hi[3 * a + 2]; z++)
                for (int32_t y = m_spheres.lo[3 * a + 1]; y <= m_spheres.hi[3 * a + 1]; y++)
                    for (int32_t x = m_spheres.lo[3 * a + 0]; x <= m_spheres.hi[3 * a + 0]; x++) {
                        const size_t bin = (size_t)x + (size_t)grid.nx * ((size_t)y + (size_t)grid.ny * (size_t)z);
                        const uint32_t* first = m_spheres.entries.data() + m_spheres.start[bin];
                        const uint32_t* last = m_spheres.entries.data() + m_spheres.start[bin + 1];
                        for (const uint32_t* it = std::upper_bound(first, last, (uint32_t)a); it != last; ++it) {
                            const uint32_t b = *it;
                            const bodyID_t oB = s.spheres.owner[b];
                            if (oB == oA || !maskRow[ow.family[oB]]) continue;
                            const double3 pB = k.spherePos[b];
                            const double eB = (double)s.spheres.radius[b] + marginOf(oB);
                            const double reach = eA + eB;
                            const double3 d = pA - pB;
                            if (fabs(d.x) > reach || fabs(d.y) > reach || fabs(d.z) > reach) continue;
                            if (!ownsPair(make_double3(pB.x - eB, pB.y - eB, pB.z - eB), x, y, z)) continue;
                            if (dot(d, d) >= reach * reach) continue;
                            partners.push_back(b);
                        }
                        if (nT == 0) continue;
                        for (uint32_t e = m_triangles.start[bin]; e < m_triangles.start[bin + 1]; e++) {
                            const uint32_t tri = m_triangles.entries[e];
                            if (!maskRow[ow.family[s.triangles.owner[tri]]]) continue;
                            const double3 lo = m_triLo[tri], hi = m_triHi[tri];
                            if (lo.x > pA.x + eA || lo.y > pA.y + eA || lo.z > pA.z + eA || hi.x < loA.x ||
                                hi.y < loA.y || hi.z < loA.z)
                                continue;
                            if (!ownsPair(lo, x, y, z)) continue;
                            const double3* v = &k.triVert[3 * tri];
                            double3 bary;
                            const double3 c = closestPointOnTriangle(pA, v[0], v[1], v[2], bary);
                            if (length(pA - c) < eA + marginOf(s.triangles.owner[tri])) triPartners.push_back(tri);
                        }
                    }
            std::sort(partners.begin(), partners.end());
            std::sort(triPartners.begin(), triPartners.end());
            auto emit = [&](bodyID_t b, uint8_t type) {
                mine.geomA.push_back((bodyID_t)a);
                mine.geomB.push_back(b);
                mine.type.push_back(type);
            };
            for (bodyID_t b : partners) emit(b, SPHERE_SPHERE);
            for (size_t j = 0; j < nA; j++) {
                if (!maskRow[ow.family[s.analytical.owner[j]]]) continue;
                const double dist = s.analytical.type[j] == ANAL_PLANE
                                        ? planeSignedDistance(pA, k.analPos[j], k.analDir[j])
                                        : cylinderSignedDistance(pA, k.analPos[j], k.analDir[j], s.analytical.radius[j],
                                                                 s.analytical.inside[j] != 0);
                if (dist < eA + marginOf(s.analytical.owner[j])) emit((bodyID_t)(nS + j), SPHERE_ANALYTICAL);
            }
            for (bodyID_t tri : triPartners) emit(triBase + tri, SPHERE_TRIANGLE);
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
