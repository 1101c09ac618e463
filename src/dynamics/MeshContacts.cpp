#include "dynamics/MeshContacts.h"

#include <algorithm>

#include "backend/cpu/Parallel.h"
#include "dynamics/ContactInputsGather.h"

namespace deme {

namespace {

// One sphere-triangle contact of the sphere being resolved.
struct Candidate {
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
bool isLocalMinimum(const SimState& s, const double3& x, const Candidate& c, const double3& bary, double tolFeature) {
    const TriangleArrays& tr = s.triangles;
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
        double3 otherBary;
        const double3 p = closestPointOnTriangle(x, w[0], w[1], w[2], otherBary);
        if (length(x - p) < c.dist - tolDist) return false;
    }
    return true;
}

// Decides which contacts of one sphere count (see MeshContacts.h) and hands history over.
void resolveSphere(SimState& s, const uint32_t* contacts, size_t n, std::vector<Candidate>& cand) {
    ContactArrays& c = s.contacts;
    const bodyID_t a = c.geomA[contacts[0]];
    const double3 x = s.cache.spherePos[a];
    const double r = s.spheres.radius[a];
    const bodyID_t triBase = s.triangleIdBase();
    cand.clear();
    for (size_t k = 0; k < n; k++) {
        const uint32_t i = contacts[k];
        const uint32_t t = c.geomB[i] - triBase;
        double3 onTri, bary;
        const ContactPoint cp = sphereTriangleGeometry(s, a, t, onTri, bary);
        Candidate cd{i, t, s.triangles.owner[t], r - cp.overlap, onTri, false};
        cd.counts = cp.overlap > 0.0 && isLocalMinimum(s, x, cd, bary, 1e-6 * r);
        cand.push_back(cd);
    }
    // Nearest first (ties by triangle id); a point already taken by a nearer or equal contact of the
    // same mesh (a seam, a vertex, a ridge) is not counted twice.
    std::sort(cand.begin(), cand.end(), [](const Candidate& p, const Candidate& q) {
        return p.dist < q.dist || (p.dist == q.dist && p.tri < q.tri);
    });
    const double tolSame = 1e-6 * r;
    for (size_t k = 0; k < cand.size(); k++) {
        if (!cand[k].counts) continue;
        for (size_t j = 0; j < k; j++)
            if (cand[j].counts && cand[j].mesh == cand[k].mesh && length(cand[j].point - cand[k].point) <= tolSame) {
                cand[k].counts = false;
                break;
            }
    }
    for (const Candidate& cd : cand)
        c.meshState[cd.contact] = (uint8_t)(((c.meshState[cd.contact] & 1u) << 1) | (cd.counts ? 1u : 0u));
    // Hand-over: a contact that starts counting takes the history of one of the same mesh that
    // stopped counting in this step, so friction carries across edges.
    const unsigned int W = s.numWildcards;
    for (const Candidate& start : cand) {
        if (c.meshState[start.contact] != 1u) continue;
        for (const Candidate& stop : cand)
            if (c.meshState[stop.contact] == 2u && stop.mesh == start.mesh) {
                for (unsigned int w = 0; w < W; w++)
                    c.wildcards[start.contact * W + w] = c.wildcards[stop.contact * W + w];
                break;
            }
    }
}

}  // namespace

void resolveMeshContacts(SimState& s) {
    const ContactArrays& c = s.contacts;
    const std::vector<uint32_t>& groups = c.meshContactGroups;
    if (groups.size() < 2) return;
    const size_t nGroups = groups.size() - 1;
#pragma omp parallel if (nGroups > PARALLEL_MIN_ITEMS / 8)
    {
        std::vector<Candidate> cand;
#pragma omp for schedule(static)
        for (size_t g = 0; g < nGroups; g++)
            resolveSphere(s, c.meshContacts.data() + groups[g], groups[g + 1] - groups[g], cand);
    }
}

}  // namespace deme
