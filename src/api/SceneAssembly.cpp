#include "api/SceneAssembly.h"

#include "api/BatchValues.h"
#include "api/ForceModelSetup.h"

#include <algorithm>
#include <cmath>
#include <parallel/algorithm>
#include <map>
#include <tuple>

#include <deme/Error.h>

#include "parallel/Parallel.h"
#include "physics/ContactGeometry.h"
#include "physics/RigidBody.h"
#include "runtime/TextFormat.h"
#include "state/OwnerCentre.h"
#include "state/SphereLayoutChoice.h"

namespace deme {

namespace {

const char* CALL = "Initialize";

DomainFrame makeFrame(const float3& lo, const float3& size, unsigned int periodicAxes, bool sheared, double rate) {
    DomainFrame f;
    f.origin = to_double3(lo);
    f.periodic = PeriodicBox{to_double3(size), periodicAxes, 0u, 0.0, 0.0, nullptr};
    // Lees–Edwards: the image above slides at rate * Lz (physics/Periodic.h).
    f.periodic.shear = sheared ? 1u : 0u;
    f.periodic.shearVelocity = sheared ? rate * (double)size.z : 0.0;
    const double maxL = std::max({(double)size.x, (double)size.y, (double)size.z});
    // The largest dimension spans all but one of the 2^21 voxels, so the far faces are representable.
    f.voxelSize = maxL / (double)((1 << VOXEL_BITS_PER_AXIS) - 1);
    f.subStep = f.voxelSize / SUBVOXEL_STEPS;
    f.parking = parkingLine(f);
    return f;
}

bool insideDomain(const double3& p, const float3& lo, const float3& size) {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= (double)lo.x + size.x && p.y <= (double)lo.y + size.y &&
           p.z <= (double)lo.z + size.z;
}

// A clump of the scene, by its batch and its index there.
struct ClumpRef {
    const DEMClumpBatch* batch;
    size_t index;
};
const float3& positionOf(const ClumpRef& c) { return c.batch->GetPositions()[c.index]; }

// The scene's clumps in user order (batch by batch), each found from its user index by its batch's
// first one: no list of the clumps is made (it was 16 B a clump at the assembly's peak).
class UserClumps {
  public:
    explicit UserClumps(const Scene& scene) {
        m_start.push_back(0);
        for (const auto& b : scene.batches) {
            m_batches.push_back(b.get());
            m_start.push_back(m_start.back() + b->GetNumClumps());
        }
    }
    size_t size() const { return m_start.back(); }
    ClumpRef operator[](size_t u) const {
        // The last batch that starts at or before u (a batch of no clumps starts where the next does).
        const size_t b = (size_t)(std::upper_bound(m_start.begin(), m_start.end(), u) - m_start.begin()) - 1;
        return ClumpRef{m_batches[b], u - m_start[b]};
    }

  private:
    std::vector<const DEMClumpBatch*> m_batches;
    std::vector<size_t> m_start;  // batch k's clumps are [m_start[k], m_start[k + 1])
};

// Capacity for n rows in every array of the owners' and the spheres' field groups.
struct ReserveRows {
    size_t n;
    template <class V>
    void operator()(V& v, V&, FieldRole role) const {
        if (role != FieldRole::RESULT) v.reserve(n);  // results: the backend's (SimState.h)
    }
};

// The owner arrays a scene gives values (the others are set for every owner at the end) sized to n.
void resizeOwnerInputs(OwnerArrays& o, size_t n) {
    o.voxel.resize(n);
    o.subX.resize(n);
    o.subY.resize(n);
    o.subZ.resize(n);
    o.oriQ.resize(n);
    o.vel.resize(n);
    o.angVel.resize(n);
    o.family.resize(n);
    o.inertia.resize(n);
}

// Owner k's values (its rows exist); false where its position is outside the frame.
bool setOwner(SimState& s, size_t k, const double3& pos, const float4& q, const float3& v, const float3& w,
              family_t fam, inertiaID_t inertia) {
    OwnerArrays& o = s.owners;
    if (!encodePosition(pos, s.frame, o.voxel[k], o.subX[k], o.subY[k], o.subZ[k])) return false;
    o.oriQ[k] = quatNormalize(q);
    o.vel[k] = v;
    o.angVel[k] = w;
    o.family[k] = fam;
    o.inertia[k] = inertia;
    return true;
}

[[noreturn]] void throwOutsideDomain(const char* what, size_t ownerIndex, const double3& pos) {
    throwError(CALL, std::string(what) + " (owner " + std::to_string(ownerIndex) + ") at (" + std::to_string(pos.x) +
                         ", " + std::to_string(pos.y) + ", " + std::to_string(pos.z) +
                         ") is outside the simulation domain");
}

void addOwner(SimState& s, const double3& pos, const float4& q, const float3& v, const float3& w, family_t fam,
              inertiaID_t inertia, size_t ownerIndex, const char* what) {
    const size_t k = s.owners.voxel.size();
    resizeOwnerInputs(s.owners, k + 1);
    if (!setOwner(s, k, pos, q, v, w, fam, inertia)) throwOutsideDomain(what, ownerIndex, pos);
}

// Appends a mesh's triangles; vertices with bit-identical coordinates are welded into one id.
void appendMeshTriangles(SimState& s, const DEMMeshConnected& mesh, bodyID_t owner) {
    TriangleArrays& t = s.triangles;
    const uint32_t base = t.vertTriStart.empty() ? 0 : (uint32_t)t.vertTriStart.size();
    std::map<std::tuple<float, float, float>, uint32_t> weld;
    std::vector<uint32_t> weldedOf(mesh.GetNumVertices());
    for (size_t i = 0; i < mesh.GetNumVertices(); i++) {
        const float3 v = mesh.GetVertices()[i];
        const auto key = std::make_tuple(v.x, v.y, v.z);
        auto it = weld.find(key);
        if (it == weld.end()) it = weld.emplace(key, base + (uint32_t)weld.size()).first;
        weldedOf[i] = it->second;
    }
    const materialID_t mat = (materialID_t)mesh.GetMaterial()->GetLoadOrder();
    for (const int3& f : mesh.GetFaces()) {
        t.owner.push_back(owner);
        t.v0.push_back(mesh.GetVertices()[f.x]);
        t.v1.push_back(mesh.GetVertices()[f.y]);
        t.v2.push_back(mesh.GetVertices()[f.z]);
        t.material.push_back(mat);
        t.vert.insert(t.vert.end(), {weldedOf[f.x], weldedOf[f.y], weldedOf[f.z]});
    }
    // Reserve this mesh's welded ids; the vertex -> triangles index is built once at the end.
    t.vertTriStart.resize(base + weld.size(), 0);
}

void finishTriangleTopology(SimState& s) {
    TriangleArrays& t = s.triangles;
    const size_t nVerts = t.vertTriStart.size();
    std::vector<uint32_t> start(nVerts + 1, 0);
    for (uint32_t v : t.vert) start[v + 1]++;
    for (size_t v = 0; v < nVerts; v++) start[v + 1] += start[v];
    t.vertTris.resize(t.vert.size());
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < t.vert.size(); i++) t.vertTris[fill[t.vert[i]]++] = (uint32_t)(i / 3);
    t.vertTriStart = std::move(start);
}

// Order of clumps along a Morton (Z-order) curve over cells of about two grain sizes; ties keep the
// user order, so the layout is deterministic.
template <typename PosOf>
std::vector<uint32_t> spatialOrder(const Scene& scene, size_t n, PosOf posOf) {
    float extent = 0.f;
    for (const auto& b : scene.batches)
        for (const auto& t : b->GetDistinctTypes()) extent = std::max(extent, t->GetExtent());
    const double cell = std::max(2.0 * extent, 1e-12);
    auto spread = [](uint64_t v) {  // 21 bits -> every third bit
        v &= 0x1FFFFF;
        v = (v | v << 32) & 0x1F00000000FFFFULL;
        v = (v | v << 16) & 0x1F0000FF0000FFULL;
        v = (v | v << 8) & 0x100F00F00F00F00FULL;
        v = (v | v << 4) & 0x10C30C30C30C30C3ULL;
        v = (v | v << 2) & 0x1249249249249249ULL;
        return v;
    };
    auto coord = [&](float x, float lo) {
        const double c = std::floor(((double)x - lo) / cell);
        return (uint64_t)std::min(std::max(c, 0.0), 2097151.0);
    };
    std::vector<uint64_t> key(n);
#pragma omp parallel for schedule(static) if (n > PARALLEL_MIN_ITEMS)
    for (size_t u = 0; u < n; u++) {
        const float3 p = posOf(u);
        key[u] = spread(coord(p.x, scene.domainLo.x)) | spread(coord(p.y, scene.domainLo.y)) << 1 |
                 spread(coord(p.z, scene.domainLo.z)) << 2;
    }
    // 32-bit indices (the caller has checked that the clumps have 32-bit ids): 4 B a clump less at the
    // assembly's peak, and as much in the parallel sort's buffer.
    std::vector<uint32_t> order(n);
    for (size_t u = 0; u < n; u++) order[u] = (uint32_t)u;
    // A stable sort's result is unique: the parallel one's is the serial one's.
    const auto byKey = [&](uint32_t a, uint32_t b) { return key[a] < key[b]; };
    if (n > PARALLEL_MIN_ITEMS && cpuThreadCount() > 1)
        __gnu_parallel::stable_sort(order.begin(), order.end(), byKey);
    else
        std::stable_sort(order.begin(), order.end(), byKey);
    return order;
}

// Whether the scene's spheres are their owners from the start: every clump is one sphere at its
// centre (what chooseSphereLayout, state/SphereLayoutChoice.h, would choose at once), unless the
// full layout is forced. Then no sphere owners, offsets and id maps are made only to be let go: 24
// B a sphere at the assembly's peak, a GPU run's host peak.
bool spheresAreOwnersFromTheStart(const Scene& scene) {
    if (fullSphereLayoutForced()) return false;
    size_t clumps = 0;
    for (const auto& b : scene.batches) {
        clumps += b->GetNumClumps();
        for (const auto& t : b->GetDistinctTypes())
            if (t->GetNumSpheres() != 1 || !isZero(t->relPos[0])) return false;
    }
    return clumps > 0;
}

// The clumps in user order (batch by batch), validated, then laid out in space-filling-curve order
// so that neighbours in space are neighbours in memory; user ids are kept in a permutation. A
// function of its own, so that its transients (the order, each clump's first sphere) are gone
// before the owners' remaining arrays are made: the assembly's peak is the host's in a GPU run.
// compact: every clump is one sphere at its centre, and the spheres are to be their owners.
void placeClumps(const Scene& scene, const std::map<const DEMClumpTemplate*, inertiaID_t>& templateIndex, bool compact,
                 SimState& s) {
    const UserClumps user(scene);
    if (user.size() >= (size_t(1) << 31)) throwError(CALL, "too many geometries for 32-bit ids");
    // The first clump outside the domain, in user order (checked in parallel: a billion-grain scene).
    size_t firstOutside = user.size();
#pragma omp parallel for schedule(static) reduction(min : firstOutside) if (user.size() > PARALLEL_MIN_ITEMS)
    for (size_t u = 0; u < user.size(); u++)
        if (!insideDomain(to_double3(positionOf(user[u])), scene.domainLo, scene.domainSize))
            firstOutside = std::min(firstOutside, u);
    if (firstOutside < user.size())
        throwError(CALL, "clump " + std::to_string(firstOutside) + " at " +
                             formatVector(positionOf(user[firstOutside])) + " is outside the simulation domain (from " +
                             formatVector(scene.domainLo) + " to " + formatVector(scene.domainLo + scene.domainSize) +
                             ")");
    const std::vector<uint32_t> order = spatialOrder(scene, user.size(), [&](size_t u) { return positionOf(user[u]); });
    // Where spheres are their owners (owner k's sphere is sphere k, at its centre, and sphere ids
    // are owner ids) the state keeps no sphere owners, offsets, id maps or first spheres.
    // Each clump's first sphere, in user order and in the spatial order the arrays take.
    std::vector<uint32_t> userSphereStart, sphereStart;
    if (!compact) {
        userSphereStart.assign(user.size() + 1, 0);
        sphereStart.assign(user.size() + 1, 0);
        for (size_t u = 0; u < user.size(); u++) {
            const ClumpRef c = user[u];
            userSphereStart[u + 1] = userSphereStart[u] + (uint32_t)c.batch->GetType(c.index)->GetNumSpheres();
        }
        for (size_t k = 0; k < order.size(); k++)
            sphereStart[k + 1] = sphereStart[k] + (userSphereStart[order[k] + 1] - userSphereStart[order[k]]);
    }
    // Every array to its final size at once: grown by doubling, the owner and sphere arrays would
    // keep up to half their bytes unused for the whole run (docs/memory.md).
    const size_t nOwnersTotal = user.size() + scene.externObjs.size() + scene.meshes.size();
    const size_t nSpheres = compact ? user.size() : sphereStart[user.size()];
    forEachOwnerField(s.owners, s.owners, ReserveRows{nOwnersTotal});
    if (compact) {
        s.spheres.radius.resize(nSpheres);
        s.spheres.material.resize(nSpheres);
        s.spheresAreOwners = s.sphereIdsAreOwnerIds = true;
        s.userSphereIds = nSpheres;
    } else {
        forEachSphereField(s.spheres, s.spheres, ReserveRows{nSpheres});
        s.spheres.owner.resize(nSpheres);
        s.spheres.relPos.resize(nSpheres);
        s.spheres.radius.resize(nSpheres);
        s.spheres.material.resize(nSpheres);
        s.sphereInternalToUser.resize(nSpheres);
    }
    s.ownerUserToInternal.reserve(nOwnersTotal);
    s.ownerInternalToUser.reserve(nOwnersTotal);
    s.ownerUserToInternal.resize(user.size());
    s.ownerInternalToUser.resize(user.size());
    // Every clump's owner row and spheres, in parallel (each writes its own rows: owner k, spheres
    // from sphereStart[k], or sphere k where spheres are their owners); the first clump whose
    // position does not encode stops Initialize.
    resizeOwnerInputs(s.owners, user.size());
    size_t firstUnencoded = user.size();
#pragma omp parallel for schedule(static) reduction(min : firstUnencoded) if (user.size() > PARALLEL_MIN_ITEMS)
    for (size_t owner = 0; owner < order.size(); owner++) {
        const size_t u = order[owner];
        const ClumpRef c = user[u];
        const DEMClumpBatch* b = c.batch;
        const size_t i = c.index;
        const DEMClumpTemplate& t = *b->GetType(i);
        s.ownerUserToInternal[u] = (bodyID_t)owner;
        s.ownerInternalToUser[owner] = (bodyID_t)u;
        if (!setOwner(s, owner, to_double3(positionOf(c)), BatchValues::oriQ(*b, i), BatchValues::vel(*b, i),
                      BatchValues::angVel(*b, i), BatchValues::family(*b, i), templateIndex.at(&t)))
            firstUnencoded = std::min(firstUnencoded, owner);
        if (compact) {
            s.spheres.radius[owner] = t.radii[0];
            s.spheres.material[owner] = (materialID_t)t.materials[0]->GetLoadOrder();
            continue;
        }
        for (size_t k = 0, at = sphereStart[owner]; k < t.GetNumSpheres(); k++, at++) {
            s.spheres.owner[at] = (bodyID_t)owner;
            s.spheres.relPos[at] = t.relPos[k];
            s.spheres.radius[at] = t.radii[k];
            s.spheres.material[at] = (materialID_t)t.materials[k]->GetLoadOrder();
            s.sphereInternalToUser[at] = userSphereStart[u] + (uint32_t)k;
        }
    }
    if (firstUnencoded < user.size())
        throwOutsideDomain("clump", order[firstUnencoded], to_double3(positionOf(user[order[firstUnencoded]])));
}

}  // namespace

SimState assembleScene(const Scene& scene, const ModelLayout& model, bool spheresMayBeOwners) {
    if (!scene.hasDomain) throwError(CALL, "no simulation domain: call InstructBoxDomainDimension first");
    if (scene.materials.empty()) throwError(CALL, "no material loaded: call LoadMaterial first");
    if (scene.batches.empty() && scene.externObjs.empty() && scene.meshes.empty())
        throwError(CALL, "the scene is empty: add clumps first");

    SimState s;
    s.frame = makeFrame(scene.domainLo, scene.domainSize, scene.periodicAxes, scene.sheared, scene.shearRate);
    s.domainSize = to_double3(scene.domainSize);
    s.numWildcards = (unsigned int)model.contactWildcards.size();
    buildMaterialTables(scene, model, s.materials);

    // Mass properties: one entry per template in use, then one per external object.
    std::map<const DEMClumpTemplate*, inertiaID_t> templateIndex;
    for (const auto& b : scene.batches)
        for (const auto& t : b->GetDistinctTypes())
            if (!templateIndex.count(t.get())) {
                templateIndex[t.get()] = (inertiaID_t)s.massProps.mass.size();
                s.massProps.mass.push_back(t->mass);
                s.massProps.moi.push_back(t->MOI);
                s.massProps.extent.push_back(t->GetExtent());
                s.massProps.dynamic.push_back(1);
            }

    placeClumps(scene, templateIndex, spheresMayBeOwners && spheresAreOwnersFromTheStart(scene), s);
    s.numClumps = s.owners.size();

    // External objects: kinematic owners made of analytical components.
    for (const auto& obj : scene.externObjs) {
        const size_t owner = s.owners.size();
        s.ownerUserToInternal.push_back((bodyID_t)owner);
        s.ownerInternalToUser.push_back((bodyID_t)owner);
        const inertiaID_t inertia = (inertiaID_t)s.massProps.mass.size();
        s.massProps.mass.push_back(obj->GetMass());
        s.massProps.moi.push_back(obj->GetMOI());
        s.massProps.extent.push_back(0.f);
        s.massProps.dynamic.push_back(0);
        addOwner(s, to_double3(obj->GetInitPos()), obj->GetInitQuat(), make_float3(0.f), make_float3(0.f),
                 obj->GetFamily(), inertia, owner, "external object");
        for (const auto& c : obj->GetComponents()) {
            s.analytical.owner.push_back((bodyID_t)owner);
            s.analytical.type.push_back((uint8_t)c.type);
            s.analytical.relPos.push_back(c.pos);
            s.analytical.relDir.push_back(c.dir);
            s.analytical.radius.push_back(c.radius);
            s.analytical.inside.push_back(c.inside ? 1 : 0);
            s.analytical.material.push_back((materialID_t)c.material->GetLoadOrder());
        }
    }

    s.numAnalyticalOwners = s.owners.size() - s.numClumps;

    // Meshes: owners made of triangles, welded per mesh for the contact rule's topology.
    for (const auto& mesh : scene.meshes) {
        const size_t owner = s.owners.size();
        s.ownerUserToInternal.push_back((bodyID_t)owner);
        s.ownerInternalToUser.push_back((bodyID_t)owner);
        const inertiaID_t inertia = (inertiaID_t)s.massProps.mass.size();
        s.massProps.mass.push_back(mesh->GetMass());
        s.massProps.moi.push_back(mesh->GetMOI());
        float extent = 0.f;
        for (const auto& v : mesh->GetVertices()) extent = std::max(extent, length(v));
        s.massProps.extent.push_back(extent);
        s.massProps.dynamic.push_back(mesh->IsFree() ? 1 : 0);
        addOwner(s, to_double3(mesh->GetInitPos()), mesh->GetInitQuat(), make_float3(0.f), make_float3(0.f),
                 mesh->GetFamily(), inertia, owner, "mesh");
        appendMeshTriangles(s, *mesh, (bodyID_t)owner);
    }
    finishTriangleTopology(s);

    const size_t nOwners = s.owners.size();
    if (!s.spheresAreOwners) rangesByOwner(nOwners, s.spheres.owner, s.ownerSphereStart);
    // (No loads or travel: the steps' results, which the backend that runs them makes: SimState.h.)
    s.integrationScratch.flags.assign(nOwners, 0);  // read by the force pass (a parked clump's) before a step
    if (!s.sphereIdsAreOwnerIds) {
        s.sphereUserToInternal.assign(s.spheres.size(), 0);
#pragma omp parallel for schedule(static) if (s.spheres.size() > PARALLEL_MIN_ITEMS)
        for (size_t i = 0; i < s.spheres.size(); i++) s.sphereUserToInternal[s.sphereInternalToUser[i]] = (bodyID_t)i;
    }
    // Owner and geometry wildcards start at 0.
    const size_t nGeometries = s.spheres.size() + s.analytical.size() + s.triangles.size();
    s.wildcards.owner.assign(model.ownerWildcards.size(), std::vector<float>(nOwners, 0.f));
    s.wildcards.geometry.assign(model.geometryWildcards.size(), std::vector<float>(nGeometries, 0.f));
    if (s.spheres.size() >= (size_t(1) << 31) || nOwners >= (size_t(1) << 31))
        throwError(CALL, "too many geometries for 32-bit ids");
    return s;
}

}  // namespace deme
