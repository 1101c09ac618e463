#include "api/SceneAssembly.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <deme/Error.h>

#include "physics/ContactGeometry.h"
#include "physics/DefaultForceModel.h"
#include "physics/RigidBody.h"

namespace deme {

namespace {

const char* CALL = "Initialize";

std::string fmt3(const float3& v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

// Pairwise table: the user's pair value, else the average of the two materials' values.
std::vector<float> pairTable(const Scene& scene, const std::string& name, double fallback) {
    const size_t n = scene.materials.size();
    std::vector<float> t(n * n);
    for (size_t a = 0; a < n; a++)
        for (size_t b = 0; b < n; b++) {
            const auto& pa = scene.materials[a]->GetProperties();
            const auto& pb = scene.materials[b]->GetProperties();
            const double va = pa.count(name) ? pa.at(name) : fallback;
            const double vb = pb.count(name) ? pb.at(name) : fallback;
            double v = 0.5 * (va + vb);
            const auto it = scene.pairProperties.find({name, (unsigned)std::min(a, b), (unsigned)std::max(a, b)});
            if (it != scene.pairProperties.end()) v = it->second;
            t[a * n + b] = (float)v;
        }
    return t;
}

DomainFrame makeFrame(const float3& lo, const float3& size) {
    DomainFrame f;
    f.origin = to_double3(lo);
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

void addOwner(SimState& s, const double3& pos, const float4& q, const float3& v, const float3& w, family_t fam,
              OwnerType type, inertiaID_t inertia, float extent, size_t ownerIndex, const char* what) {
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
    o.extent.push_back(extent);
}

}  // namespace

SimState assembleScene(const Scene& scene) {
    if (!scene.hasDomain) throwError(CALL, "no simulation domain: call InstructBoxDomainDimension first");
    if (scene.materials.empty()) throwError(CALL, "no material loaded: call LoadMaterial first");
    if (scene.batches.empty() && scene.externObjs.empty()) throwError(CALL, "the scene is empty: add clumps first");

    SimState s;
    s.frame = makeFrame(scene.domainLo, scene.domainSize);
    s.domainSize = to_double3(scene.domainSize);
    s.numWildcards = DEFAULT_MODEL_NUM_WILDCARDS;

    // Materials.
    MaterialTables& mt = s.materials;
    mt.count = (unsigned int)scene.materials.size();
    for (const auto& m : scene.materials) {
        mt.E.push_back((float)m->Get("E"));
        mt.nu.push_back((float)m->Get("nu"));
    }
    mt.CoR = pairTable(scene, "CoR", 0.0);
    mt.mu = pairTable(scene, "mu", 0.0);
    mt.Crr = pairTable(scene, "Crr", 0.0);

    // Mass properties: one entry per template in use, then one per external object.
    std::map<const DEMClumpTemplate*, inertiaID_t> templateIndex;
    for (const auto& b : scene.batches)
        for (const auto& t : b->GetTypes())
            if (!templateIndex.count(t.get())) {
                templateIndex[t.get()] = (inertiaID_t)s.massProps.mass.size();
                s.massProps.mass.push_back(t->mass);
                s.massProps.moi.push_back(t->MOI);
            }

    // Clumps, then their spheres (contiguous per owner).
    for (const auto& b : scene.batches) {
        const size_t n = b->GetNumClumps();
        for (size_t i = 0; i < n; i++) {
            const DEMClumpTemplate& t = *b->GetTypes()[i];
            const size_t owner = s.owners.size();
            const double3 pos = to_double3(b->GetPositions()[i]);
            const float4 q = b->GetOriQs()[i];
            if (!insideDomain(pos, scene.domainLo, scene.domainSize))
                throwError(CALL, "clump " + std::to_string(owner) + " at " + fmt3(b->GetPositions()[i]) +
                                     " is outside the simulation domain (from " + fmt3(scene.domainLo) + " to " +
                                     fmt3(scene.domainLo + scene.domainSize) + ")");
            addOwner(s, pos, q, b->GetVelocities()[i], b->GetAngVelocities()[i], b->GetFamilies()[i],
                     OWNER_CLUMP, templateIndex.at(&t), t.GetExtent(), owner, "clump");
            for (size_t k = 0; k < t.GetNumSpheres(); k++) {
                s.spheres.owner.push_back((bodyID_t)owner);
                s.spheres.relPos.push_back(t.relPos[k]);
                s.spheres.radius.push_back(t.radii[k]);
                s.spheres.material.push_back((materialID_t)t.materials[k]->GetLoadOrder());
            }
        }
    }
    s.numClumps = s.owners.size();

    // External objects: kinematic owners made of analytical components.
    for (const auto& obj : scene.externObjs) {
        const size_t owner = s.owners.size();
        const inertiaID_t inertia = (inertiaID_t)s.massProps.mass.size();
        s.massProps.mass.push_back(obj->GetMass());
        s.massProps.moi.push_back(obj->GetMOI());
        addOwner(s, to_double3(obj->GetInitPos()), obj->GetInitQuat(), make_float3(0.f), make_float3(0.f),
                 obj->GetFamily(), OWNER_ANALYTICAL, inertia, 0.f, owner, "external object");
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

    const size_t nOwners = s.owners.size();
    s.owners.contactForce.assign(nOwners, make_float3(0.f));
    s.owners.contactTorque.assign(nOwners, make_float3(0.f));
    s.owners.extraAcc.assign(nOwners, make_float3(0.f));
    s.owners.extraAngAcc.assign(nOwners, make_float3(0.f));
    s.owners.travel.assign(nOwners, 0.f);
    if (s.spheres.size() >= (size_t(1) << 31) || nOwners >= (size_t(1) << 31))
        throwError(CALL, "too many geometries for 32-bit ids");
    return s;
}

}  // namespace deme
