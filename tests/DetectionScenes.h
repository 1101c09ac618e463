// Scenes for the contact-detection tests (CPU against brute force, GPU kernels against the CPU).
#pragma once

#include <memory>
#include <random>
#include <vector>

#include "api/Scene.h"
#include "api/ForceModelSetup.h"
#include "api/SceneAssembly.h"
#include "dynamics/KinematicCache.h"
#include "runtime/FamilyRules.h"

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

// The scene as detection sees it: assembled with the default model, geometry positions computed.
inline SimState detectionState(const Scene& scene, const char* call) {
    SimState s = assembleScene(
        scene, resolveModelLayout(DEMForceModel(DEMForceModel::Kind::FRICTIONAL_HERTZIAN), scene, call));
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

}  // namespace deme_test
