#include "dynamics/MeshContacts.h"

#include "backend/cpu/Parallel.h"
#include "dynamics/ContactInputsGather.h"

namespace deme {

namespace {

// Barycentric coordinates below this count as zero: the point lies on that edge or vertex.
constexpr double ON_FEATURE = 1e-7;

// Whether sphere a's contact with triangle t counts (see the rule in MeshContacts.h).
bool contactCounts(const SimState& s, bodyID_t a, uint32_t t) {
    double3 onTri, bary;
    const ContactPoint cp = sphereTriangleGeometry(s, a, t, onTri, bary);
    if (!(cp.overlap > 0.0)) return false;
    const int small = (bary.x < ON_FEATURE) + (bary.y < ON_FEATURE) + (bary.z < ON_FEATURE);
    if (small == 0) return true;  // inside the face
    const TriangleArrays& tr = s.triangles;
    const uint32_t* vert = &tr.vert[3 * t];
    // The feature holding the point: the vertex with weight ~1, or the edge opposite the ~0 weight.
    uint32_t v0, v1;
    if (small >= 2) {
        v0 = v1 = bary.x >= bary.y && bary.x >= bary.z ? vert[0] : bary.y >= bary.z ? vert[1] : vert[2];
    } else {
        v0 = bary.x < ON_FEATURE ? vert[1] : vert[0];
        v1 = bary.z < ON_FEATURE ? vert[1] : vert[2];
    }
    const double3 x = s.cache.spherePos[a];
    const double dist = s.spheres.radius[a] - cp.overlap;
    const double tol = 1e-7 * s.spheres.radius[a];
    for (uint32_t e = tr.vertTriStart[v0]; e < tr.vertTriStart[v0 + 1]; e++) {
        const uint32_t other = tr.vertTris[e];
        if (other == t) continue;
        const uint32_t* ov = &tr.vert[3 * other];
        if (v1 != v0 && ov[0] != v1 && ov[1] != v1 && ov[2] != v1) continue;  // does not hold the edge
        double3 otherBary;
        const double3* w = &s.cache.triVert[3 * other];
        const double3 otherPt = closestPointOnTriangle(x, w[0], w[1], w[2], otherBary);
        const double otherDist = length(x - otherPt);
        if (otherDist < dist - tol) return false;                           // not a local minimum
        if (length(otherPt - onTri) <= tol && other < t) return false;      // shared point, lower id owns it
    }
    return true;
}

constexpr size_t NONE = ~size_t(0);

// A contact of the same sphere and mesh as contact i that stopped counting in this step. The
// sphere's contacts are contiguous in the sorted set, so the search is local.
size_t stoppedSibling(const SimState& s, size_t i) {
    const ContactArrays& c = s.contacts;
    const bodyID_t a = c.geomA[i];
    const bodyID_t triBase = s.triangleIdBase();
    const bodyID_t mesh = s.triangles.owner[c.geomB[i] - triBase];
    auto matches = [&](size_t j) {
        return c.type[j] == SPHERE_TRIANGLE && c.meshState[j] == 2u && s.triangles.owner[c.geomB[j] - triBase] == mesh;
    };
    for (size_t j = i; j-- > 0 && c.geomA[j] == a;)
        if (matches(j)) return j;
    for (size_t j = i + 1; j < c.size() && c.geomA[j] == a; j++)
        if (matches(j)) return j;
    return NONE;
}

}  // namespace

void resolveMeshContacts(SimState& s) {
    ContactArrays& c = s.contacts;
    const std::vector<uint32_t>& idx = c.meshContacts;
    const size_t n = idx.size();
    if (n == 0) return;
    const bodyID_t triBase = s.triangleIdBase();
#pragma omp parallel for schedule(static) if (n > PARALLEL_MIN_ITEMS / 4)
    for (size_t k = 0; k < n; k++) {
        const uint32_t i = idx[k];
        const uint8_t prev = c.meshState[i] & 1u;
        const bool now = contactCounts(s, c.geomA[i], c.geomB[i] - triBase);
        c.meshState[i] = (uint8_t)((prev << 1) | (now ? 1u : 0u));
    }
    // Hand-over: a contact that starts counting takes the history of a contact of the same sphere
    // and mesh that stopped counting in this step. Only wildcards of starting contacts are written,
    // and only those of stopping contacts are read, so the loop has no races.
    const unsigned int W = s.numWildcards;
#pragma omp parallel for schedule(static) if (n > PARALLEL_MIN_ITEMS / 4)
    for (size_t k = 0; k < n; k++) {
        const uint32_t i = idx[k];
        if (c.meshState[i] != 1u) continue;  // not a contact that starts counting now
        const size_t j = stoppedSibling(s, i);
        if (j != NONE)
            for (unsigned int w = 0; w < W; w++) c.wildcards[i * W + w] = c.wildcards[j * W + w];
    }
}

}  // namespace deme
