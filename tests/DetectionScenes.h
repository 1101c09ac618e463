// Scenes for the contact-detection tests (CPU against brute force, GPU kernels against the CPU).
#pragma once

#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <vector>

#include "api/Scene.h"
#include "api/ForceModelSetup.h"
#include "api/SceneAssembly.h"
#include "dynamics/KinematicCache.h"
#include "physics/ContactGeometry.h"
#include "physics/RigidBody.h"
#include "runtime/FamilyRules.h"

#include "MeshBuilders.h"

namespace deme_test {

using namespace deme;

// Random polydisperse spheres and 2-4-sphere clumps in a 4 cm box with two analytical walls.
inline Scene randomScene(unsigned seed, size_t nClumps) {
    Scene sc;
    sc.hasDomain = true;
    sc.domainSize = make_float3(0.04f, 0.04f, 0.04f);
    sc.domainLo = make_float3(-0.02f, -0.02f, -0.02f);
    auto mat = std::make_shared<DEMMaterial>(
        std::map<std::string, double>{{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}}, 0);
    sc.materials.push_back(mat);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.018f, 0.018f), rad(0.0003f, 0.002f), off(-0.002f, 0.002f), qd(-1.f, 1.f);
    std::uniform_int_distribution<int> nsph(1, 4), fam(0, 2);
    std::vector<std::shared_ptr<DEMClumpTemplate>> types;
    std::vector<float3> pos;
    std::vector<float4> ori;
    std::vector<unsigned int> fams;
    for (size_t i = 0; i < nClumps; i++) {
        auto t = std::make_shared<DEMClumpTemplate>();
        t->mass = 1.f;
        t->MOI = make_float3(1.f);
        const int k = nsph(rng);
        for (int j = 0; j < k; j++) {
            t->radii.push_back(rad(rng));
            t->relPos.push_back(j == 0 ? make_float3(0.f) : make_float3(off(rng), off(rng), off(rng)));
            t->materials.push_back(mat);
        }
        types.push_back(t);
        pos.push_back(make_float3(u(rng), u(rng), u(rng)));
        ori.push_back(make_float4(qd(rng), qd(rng), qd(rng), qd(rng)));
        fams.push_back((unsigned)fam(rng));
    }
    auto batch = std::make_shared<DEMClumpBatch>(types, pos);
    batch->SetOriQ(ori);
    batch->SetFamily(fams);
    sc.batches.push_back(batch);
    auto walls = std::make_shared<DEMExternObj>();
    walls->AddPlane(make_float3(0, 0, -0.017f), make_float3(0, 0, 1), mat);
    walls->AddCylinder(make_float3(0, 0, 0), make_float3(0, 0, 1), 0.017f, mat, 0);
    walls->SetFamily(1);
    sc.externObjs.push_back(walls);
    return sc;
}

// randomScene on a tessellated floor (a 16 x 16 grid of 2.5 mm cells at z = -15 mm, family 1): many
// sphere-triangle pairs.
inline Scene randomSceneOnMeshFloor(unsigned seed, size_t nClumps) {
    Scene sc = randomScene(seed, nClumps);
    auto floor =
        std::make_shared<DEMMeshConnected>(gridFloor(-0.02f, -0.02f, -0.015f, 16, 0.0025f, sc.materials.front()));
    floor->SetFamily(1);
    sc.meshes.push_back(floor);
    return sc;
}

// Random polydisperse spheres and clumps filling a 4 cm box periodic along `axes` (InstructBoxDomain
// Periodicity bits), many of them reaching over the faces; with a floor plane if z is not periodic.
inline Scene randomPeriodicScene(unsigned seed, size_t nClumps, unsigned int axes) {
    Scene sc = randomScene(seed, nClumps);
    sc.periodicAxes = axes;
    std::mt19937 rng(seed + 100);
    std::uniform_real_distribution<float> u(-0.0199f, 0.0199f);
    std::vector<float3> pos(nClumps);
    for (float3& p : pos) p = make_float3(u(rng), u(rng), u(rng));
    auto batch = std::make_shared<DEMClumpBatch>(sc.batches[0]->GetTypes(), pos);
    batch->SetOriQ(sc.batches[0]->GetOriQs());
    const std::vector<family_t>& f = sc.batches[0]->GetFamilies();
    batch->SetFamily(std::vector<unsigned int>(f.begin(), f.end()));
    sc.batches[0] = batch;
    // The walls: a floor (parallel to x and y) where z is bounded, none otherwise.
    sc.externObjs.clear();
    if (!(axes & 4u)) {
        auto floor = std::make_shared<DEMExternObj>();
        floor->AddPlane(make_float3(0, 0, -0.017f), make_float3(0, 0, 1), sc.materials[0]);
        floor->SetFamily(1);
        sc.externObjs.push_back(floor);
    }
    return sc;
}

// The scene as detection sees it: assembled with the default model, geometry positions computed.
inline SimState detectionState(const Scene& scene, const char* call) {
    SimState s =
        assembleScene(scene, resolveModelLayout(DEMForceModel(DEMForceModel::Kind::FRICTIONAL_HERTZIAN), scene, call));
    refreshKinematicCache(s);
    return s;
}

// The family rules the detection tests use with randomScene: families 0 and 2 do not touch, and
// family 1 (the walls, and meshes put in it) reaches 0.2 mm further (SetFamilyExtraMargin).
struct DetectionRules {
    FamilyRules rules;
    float extra[NUM_FAMILIES] = {};
    DetectionRules() {
        rules.setContact(0, 2, false);
        extra[1] = 2e-4f;
    }
};

// Every pair within reach by an O(N^2) search: spheres (a < b) and sphere-analytical pairs.
inline std::set<std::pair<bodyID_t, bodyID_t>> bruteForce(const SimState& s, double margin, const uint8_t* mask,
                                                          const float* extra) {
    std::set<std::pair<bodyID_t, bodyID_t>> pairs;
    const size_t nS = s.spheres.size();
    std::vector<double3> p(nS);
    for (size_t i = 0; i < nS; i++) {
        const bodyID_t o = s.spheres.owner[i];
        const double3 op =
            decodePosition(s.owners.voxel[o], s.owners.subX[o], s.owners.subY[o], s.owners.subZ[o], s.frame);
        p[i] = localPointToGlobal(op, s.owners.oriQ[o], s.spheres.relPos[i]);
    }
    auto famOf = [&](bodyID_t o) { return (size_t)s.owners.family[o]; };
    auto m = [&](bodyID_t o) { return margin + (double)extra[famOf(o)]; };
    for (size_t a = 0; a < nS; a++) {
        for (size_t b = a + 1; b < nS; b++) {
            const bodyID_t oa = s.spheres.owner[a], ob = s.spheres.owner[b];
            if (oa == ob || !mask[famOf(oa) * NUM_FAMILIES + famOf(ob)]) continue;
            const double reach = ((double)s.spheres.radius[a] + m(oa)) + ((double)s.spheres.radius[b] + m(ob));
            double3 d = p[a] - p[b];
            // Across periodic faces: the nearest image (an independent minimum-image rule). In a
            // sheared cell the image k cells above is displaced along x by k times the offset.
            const PeriodicBox& pb = s.frame.periodic;
            if (pb.axes & 4u) {
                const double k = std::round(d.z / pb.length.z);
                d.z -= pb.length.z * k;
                if (pb.shear) {
                    const double u = pb.shearVelocity * pb.shearTime;
                    d.x -= k * (u - pb.length.x * std::round(u / pb.length.x));
                }
            }
            if (pb.axes & 1u) d.x -= pb.length.x * std::round(d.x / pb.length.x);
            if (pb.axes & 2u) d.y -= pb.length.y * std::round(d.y / pb.length.y);
            if (dot(d, d) < reach * reach) pairs.insert({(bodyID_t)a, (bodyID_t)b});
        }
        for (size_t k = 0; k < s.analytical.size(); k++) {
            const bodyID_t ob = s.analytical.owner[k];
            if (!mask[famOf(s.spheres.owner[a]) * NUM_FAMILIES + famOf(ob)]) continue;
            const double3 wp = to_double3(s.analytical.relPos[k]);
            const double3 wd = to_double3(s.analytical.relDir[k]);
            const double dist =
                s.analytical.type[k] == ANAL_PLANE
                    ? planeSignedDistance(p[a], wp, wd)
                    : cylinderSignedDistance(p[a], wp, wd, s.analytical.radius[k], s.analytical.inside[k] != 0);
            if (dist < ((double)s.spheres.radius[a] + m(s.spheres.owner[a])) + m(ob))
                pairs.insert({(bodyID_t)a, (bodyID_t)(nS + k)});
        }
    }
    return pairs;
}

// The active box's family change in the detection tests: the first clump of family `dormant` wakes
// up (to `active`) and the first of family `active` falls dormant. Whether both were found.
inline bool wakeOneAndFreezeOne(SimState& s, family_t dormant, family_t active) {
    size_t woke = 0, slept = 0;
    for (size_t o = 0; o < s.numClumps && (woke == 0 || slept == 0); o++) {
        if (s.owners.family[o] == dormant && woke == 0)
            s.owners.family[o] = active, woke = o + 1;
        else if (s.owners.family[o] == active && slept == 0)
            s.owners.family[o] = dormant, slept = o + 1;
    }
    return woke && slept;
}

}  // namespace deme_test
