// The smooth-surface rule for sphere-triangle contacts (see MeshContacts.h), per sphere, written
// once over the state type (SimState on the CPU, a StateView of device memory on the GPU).
#pragma once

#include "dynamics/ContactInputsGather.h"
#include "state/SphereLayout.h"

namespace deme {

// Most overlapping sphere-triangle contacts one sphere may have on the GPU, whose kernel sorts them
// in a local array (a larger count stops the run with an error naming the sphere).
constexpr unsigned int MAX_MESH_CANDIDATES = 64;

// One sphere-triangle contact of the sphere being resolved.
struct MeshCandidate {
    uint32_t contact;
    uint32_t tri;
    bodyID_t mesh;
    double dist;  // centre to the closest point
    double3 point;
    bool counts;
};

// Whether candidate c is a local minimum of the distance to the mesh: if its closest point lies on
// (within `tolFeature` of) an edge or vertex of its triangle, no triangle sharing that feature may be
// closer to the sphere centre x.
template <class S>
DEME_HD_INLINE bool isLocalMinimum(const S& s, const double3& x, const MeshCandidate& c, const double3& bary,
                                   double tolFeature) {
    const auto& tr = s.triangles;
    const double3* v = &s.cache.triVert[3 * c.tri];
    // Distance from the point to the edge opposite each vertex: barycentric weight x altitude.
    const double3 n = cross(v[1] - v[0], v[2] - v[0]);
    const double twiceArea = length(n);
    const double h0 = twiceArea / length(v[2] - v[1]), h1 = twiceArea / length(v[0] - v[2]),
                 h2 = twiceArea / length(v[1] - v[0]);
    const bool near0 = bary.x * h0 < tolFeature, near1 = bary.y * h1 < tolFeature, near2 = bary.z * h2 < tolFeature;
    const int nearCount = near0 + near1 + near2;
    if (nearCount == 0) return true;  // inside the face
    const uint32_t* vert = &tr.vert[3 * c.tri];
    // The feature: the edge opposite the one small weight, or the vertex with the large weight.
    uint32_t va, vb;
    if (nearCount >= 2) {
        va = vb = !near0 ? vert[0] : !near1 ? vert[1] : vert[2];
    } else {
        va = near0 ? vert[1] : vert[0];
        vb = near2 ? vert[1] : vert[2];
    }
    // "Closer" beyond rounding only. A neighbour's point within this much of our distance lies within
    // about 4e-8 c.dist of our point (the distance grows quadratically off the minimum), well inside
    // the coincidence tolerance (1e-6 r) that then removes the duplicate.
    const double tolDist = 4.0 * 2.220446049250313e-16 * c.dist;
    for (uint32_t e = tr.vertTriStart[va]; e < tr.vertTriStart[va + 1]; e++) {
        const uint32_t other = tr.vertTris[e];
        if (other == c.tri) continue;
        const uint32_t* ov = &tr.vert[3 * other];
        if (vb != va && ov[0] != vb && ov[1] != vb && ov[2] != vb) continue;  // does not hold the edge
        const double3* w = &s.cache.triVert[3 * other];
        const double3 shift = triangleImageShift(s, other, x);  // across a periodic face
        double3 otherBary;
        const double3 p = closestPointOnTriangle(x, w[0] + shift, w[1] + shift, w[2] + shift, otherBary);
        if (length(x - p) < c.dist - tolDist) return false;
    }
    return true;
}

// Decides which contacts of sphere `a` count (see MeshContacts.h) and hands history over. The
// sphere's triangle contacts are the n contacts from `first` on (contacts are sorted by sphere, and a
// sphere's triangle contacts come last). Only overlapping contacts can count; those are sorted in
// `cand`, which has room for `capacity`. Returns false (changing nothing) if they do not fit.
// `historyAt(i)`: contact i's W history floats, `historyAt.meshState(i)` its mesh state (the pooled
// forms give every sphere-triangle pair a slot, state/PooledHistory.h and state/HistoryPool.h).
template <class S, class HistoryAt>
DEME_HD_INLINE bool resolveSphereMeshContactsWith(S& s, bodyID_t a, size_t first, size_t n, MeshCandidate* cand,
                                                  size_t capacity, const HistoryAt& historyAt) {
    auto& c = s.contacts;
    const double3 x = sphereCentre(s, a);
    const double r = s.spheres.radius[a];
    const bodyID_t triBase = s.triangleIdBase();
    size_t m = 0;
    for (size_t k = 0; k < n; k++) {
        const uint32_t i = (uint32_t)(first + k);
        const uint32_t t = c.geomB[i] - triBase;
        double3 onTri, bary;
        const ContactPoint cp = sphereTriangleGeometry(s, a, t, onTri, bary);
        if (!(cp.overlap > 0.0)) continue;
        if (m == capacity) return false;
        MeshCandidate cd{i, t, s.triangles.owner[t], r - cp.overlap, onTri, false};
        cd.counts = isLocalMinimum(s, x, cd, bary, 1e-6 * r);
        // Insertion in order: nearest first, ties by triangle id (a sphere has few candidates).
        size_t at = m++;
        while (at > 0 && (cd.dist < cand[at - 1].dist || (cd.dist == cand[at - 1].dist && cd.tri < cand[at - 1].tri))) {
            cand[at] = cand[at - 1];
            at--;
        }
        cand[at] = cd;
    }
    // A point already taken by a nearer or equal contact of the same mesh (a seam, a vertex, a
    // ridge) is not counted twice.
    const double tolSame = 1e-6 * r;
    for (size_t k = 0; k < m; k++) {
        if (!cand[k].counts) continue;
        for (size_t j = 0; j < k; j++)
            if (cand[j].counts && cand[j].mesh == cand[k].mesh && length(cand[j].point - cand[k].point) <= tolSame) {
                cand[k].counts = false;
                break;
            }
    }
    // Bit 1: counted in the previous step; bit 0: counts now (only candidates can).
    for (size_t k = 0; k < n; k++) {
        uint8_t& state = historyAt.meshState(first + k);
        state = (uint8_t)((state & 1u) << 1);
    }
    for (size_t k = 0; k < m; k++)
        if (cand[k].counts) historyAt.meshState(cand[k].contact) |= 1u;
    // Hand-over: a contact that starts counting takes the history of the nearest contact of the
    // same mesh that stopped counting in this step, so friction carries across edges.
    const unsigned int W = s.numWildcards;
    for (size_t k = 0; k < m; k++) {
        const MeshCandidate& start = cand[k];
        if (historyAt.meshState(start.contact) != 1u) continue;
        size_t best = n;
        double bestDist = 0.0;
        uint32_t bestTri = 0;
        for (size_t j = 0; j < n; j++) {
            const uint32_t i = (uint32_t)(first + j);
            if (historyAt.meshState(i) != 2u) continue;
            const uint32_t t = c.geomB[i] - triBase;
            if (s.triangles.owner[t] != start.mesh) continue;
            double3 onTri, bary;
            const double dist = r - sphereTriangleGeometry(s, a, t, onTri, bary).overlap;
            if (best == n || dist < bestDist || (dist == bestDist && t < bestTri)) {
                best = j;
                bestDist = dist;
                bestTri = t;
            }
        }
        if (best == n) continue;
        float* to = historyAt(start.contact);
        const float* from = historyAt(first + best);
        for (unsigned int w = 0; w < W; w++) to[w] = from[w];
    }
    return true;
}

// A contact's history where the set keeps W floats per pair, and its mesh state (per pair).
struct HistoryInSet {
    float* wildcards;
    uint8_t* meshStates;
    unsigned int W;
    DEME_HD_INLINE float* operator()(size_t i) const { return wildcards + i * W; }
    DEME_HD_INLINE uint8_t& meshState(size_t i) const { return meshStates[i]; }
};

template <class S>
DEME_HD_INLINE bool resolveSphereMeshContacts(S& s, size_t first, size_t n, MeshCandidate* cand, size_t capacity) {
    return resolveSphereMeshContactsWith(s, pairAOf(s, first), first, n, cand, capacity,
                                         HistoryInSet{s.contacts.wildcards, s.contacts.meshState, s.numWildcards});
}

}  // namespace deme
