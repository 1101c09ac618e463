#include "api/SceneAssembly.h"

#include "api/BatchValues.h"
#include "api/ForceModelSetup.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <deme/Error.h>

#include "physics/ContactGeometry.h"
#include "physics/RigidBody.h"
#include "runtime/TextFormat.h"

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
    return f;
}

bool insideDomain(const double3& p, const float3& lo, const float3& size) {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= (double)lo.x + size.x && p.y <= (double)lo.y + size.y &&
           p.z <= (double)lo.z + size.z;
}

// Capacity for n rows in every array of the owners' and the spheres' field groups.
struct ReserveRows {
    size_t n;
    template <class V>
    void operator()(V& v, V&, FieldRole) const {
        v.reserve(n);
    }
};

void addOwner(SimState& s, const double3& pos, const float4& q, const float3& v, const float3& w, family_t fam,
              OwnerType type, inertiaID_t inertia, size_t ownerIndex, const char* what) {
    OwnerArrays& o = s.owners;
    voxelID_t vox;
    subVoxelPos_t sx, sy, sz;
    if (!encodePosition(pos, s.frame, vox, sx, sy, sz))
        throwError(CALL, std::string(what) + " (owner " + std::to_string(ownerIndex) + ") at (" +
                             std::to_string(pos.x) + ", " + std::to_string(pos.y) + ", " + std::to_string(pos.z) +
                             ") is outside the simulation domain");
    o.voxel.push_back(vox);
    o.subX.push_back(sx);
    o.subY.push_back(sy);
    o.subZ.push_back(sz);
    o.oriQ.push_back(quatNormalize(q));
    o.vel.push_back(v);
    o.angVel.push_back(w);
    o.family.push_back(fam);
    o.type.push_back((uint8_t)type);
    o.inertia.push_back(inertia);
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
std::vector<size_t> spatialOrder(const Scene& scene, size_t n, PosOf posOf) {
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
    for (size_t u = 0; u < n; u++) {
        const float3 p = posOf(u);
        key[u] = spread(coord(p.x, scene.domainLo.x)) | spread(coord(p.y, scene.domainLo.y)) << 1 |
                 spread(coord(p.z, scene.domainLo.z)) << 2;
    }
    std::vector<size_t> order(n);
    for (size_t u = 0; u < n; u++) order[u] = u;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key[a] < key[b]; });
    return order;
}

}  // namespace

SimState assembleScene(const Scene& scene, const ModelLayout& model) {
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

    // Clumps in user order (batch by batch), validated, then laid out in space-filling-curve order
    // so that neighbours in space are neighbours in memory; user ids are kept in a permutation.
    struct ClumpRef {
        const DEMClumpBatch* batch;
        size_t index;
    };
    std::vector<ClumpRef> user;
    for (const auto& b : scene.batches)
        for (size_t i = 0; i < b->GetNumClumps(); i++) {
            const float3 p = b->GetPositions()[i];
            if (!insideDomain(to_double3(p), scene.domainLo, scene.domainSize))
                throwError(CALL, "clump " + std::to_string(user.size()) + " at " + formatVector(p) +
                                     " is outside the simulation domain (from " + formatVector(scene.domainLo) + " to " +
                                     formatVector(scene.domainLo + scene.domainSize) + ")");
            user.push_back({b.get(), i});
        }
    const std::vector<size_t> order =
        spatialOrder(scene, user.size(), [&](size_t u) { return user[u].batch->GetPositions()[user[u].index]; });
    std::vector<uint32_t> userSphereStart(user.size() + 1, 0);
    for (size_t u = 0; u < user.size(); u++)
        userSphereStart[u + 1] =
            userSphereStart[u] + (uint32_t)user[u].batch->GetType(user[u].index)->GetNumSpheres();
    // Every array to its final size at once: grown by doubling, the owner and sphere arrays would
    // keep up to half their bytes unused for the whole run (docs/memory.md).
    const size_t nOwnersTotal = user.size() + scene.externObjs.size() + scene.meshes.size();
    forEachOwnerField(s.owners, s.owners, ReserveRows{nOwnersTotal});
    forEachSphereField(s.spheres, s.spheres, ReserveRows{userSphereStart[user.size()]});
    s.ownerUserToInternal.reserve(nOwnersTotal);
    s.ownerInternalToUser.reserve(nOwnersTotal);
    s.ownerUserToInternal.resize(user.size());
    s.ownerInternalToUser.resize(user.size());
    s.sphereInternalToUser.reserve(userSphereStart[user.size()]);
    for (size_t u : order) {
        const DEMClumpBatch* b = user[u].batch;
        const size_t i = user[u].index;
        const DEMClumpTemplate& t = *b->GetType(i);
        const size_t owner = s.owners.size();
        s.ownerUserToInternal[u] = (bodyID_t)owner;
        s.ownerInternalToUser[owner] = (bodyID_t)u;
        addOwner(s, to_double3(b->GetPositions()[i]), BatchValues::oriQ(*b, i), BatchValues::vel(*b, i),
                 BatchValues::angVel(*b, i), BatchValues::family(*b, i), OWNER_CLUMP, templateIndex.at(&t), u, "clump");
        for (size_t k = 0; k < t.GetNumSpheres(); k++) {
            s.spheres.owner.push_back((bodyID_t)owner);
            s.spheres.relPos.push_back(t.relPos[k]);
            s.spheres.radius.push_back(t.radii[k]);
            s.spheres.material.push_back((materialID_t)t.materials[k]->GetLoadOrder());
            s.sphereInternalToUser.push_back(userSphereStart[u] + (uint32_t)k);
        }
    }
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
                 obj->GetFamily(), OWNER_ANALYTICAL, inertia, owner, "external object");
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
                 mesh->GetFamily(), OWNER_MESH, inertia, owner, "mesh");
        appendMeshTriangles(s, *mesh, (bodyID_t)owner);
    }
    finishTriangleTopology(s);

    const size_t nOwners = s.owners.size();
    rangesByOwner(nOwners, s.spheres.owner, s.ownerSphereStart);
    s.owners.contactForce.assign(nOwners, make_float3(0.f));
    s.owners.contactTorque.assign(nOwners, make_float3(0.f));
    s.owners.travel.assign(nOwners, 0.f);
    s.integrationScratch.flags.assign(nOwners, 0);  // read by the force pass (a parked clump's) before a step
    s.sphereUserToInternal.assign(s.spheres.size(), 0);
    for (size_t i = 0; i < s.spheres.size(); i++) s.sphereUserToInternal[s.sphereInternalToUser[i]] = (bodyID_t)i;
    // Owner and geometry wildcards start at 0.
    const size_t nGeometries = s.spheres.size() + s.analytical.size() + s.triangles.size();
    s.wildcards.owner.assign(model.ownerWildcards.size(), std::vector<float>(nOwners, 0.f));
    s.wildcards.geometry.assign(model.geometryWildcards.size(), std::vector<float>(nGeometries, 0.f));
    if (s.spheres.size() >= (size_t(1) << 31) || nOwners >= (size_t(1) << 31))
        throwError(CALL, "too many geometries for 32-bit ids");
    return s;
}

}  // namespace deme
