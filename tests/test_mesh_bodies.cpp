// Meshes as bodies in a granular bed: a meshed box as container, a free falling cube, a driven blade.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "BackendFixture.h"
#include "MeshBuilders.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(MeshBodies);

namespace {

constexpr double R = 0.005, DENSITY = 2600, G = 9.81;

// About 1000 jittered spheres above the floor z = -0.05 inside |x|, |y| < 0.05.
std::vector<float3> bedPoints() {
    std::vector<float3> pts =
        GridSampler(2.2f * (float)R).SampleBox(make_float3(0, 0, 0.f), make_float3(0.043f, 0.043f, 0.04f));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> j(-0.05f * (float)R, 0.05f * (float)R);
    for (auto& p : pts) p = p + make_float3(j(rng), j(rng), j(rng));
    return pts;
}

// Settles the bed in a box [-0.05, 0.05]^2 x [-0.05, 0.1] made of a mesh or of analytical planes,
// all frictionless (so the side walls carry no weight); returns floor force / bed weight.
double floorLoadRatio(bool meshBox) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto grain = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.5, 0.02));
    auto wall = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.0));
    sim.SetMaterialPropertyPair("mu", grain, wall, 0.0);
    sim.SetMaterialPropertyPair("Crr", grain, wall, 0.0);
    sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.3f);
    std::shared_ptr<DEMTracker> floorTracker, wallsTracker;
    if (meshBox) {
        auto box = sim.AddWavefrontMeshObject(
            boxMesh(make_float3(-0.05f, -0.05f, -0.05f), make_float3(0.05f, 0.05f, 0.1f), wall));
        floorTracker = sim.Track(box);  // the box carries the load through its floor
    } else {
        auto walls = sim.AddExternalObject();
        walls->AddPlane(make_float3(-0.05f, 0, 0), make_float3(1, 0, 0), wall);
        walls->AddPlane(make_float3(0.05f, 0, 0), make_float3(-1, 0, 0), wall);
        walls->AddPlane(make_float3(0, -0.05f, 0), make_float3(0, 1, 0), wall);
        walls->AddPlane(make_float3(0, 0.05f, 0), make_float3(0, -1, 0), wall);
        floorTracker = sim.Track(sim.AddBCPlane(make_float3(0, 0, -0.05f), make_float3(0, 0, 1), wall));
    }
    const auto pts = bedPoints();
    sim.AddClumps(sim.LoadSphereType((float)sphereMass(R, DENSITY), (float)R, grain), pts);
    sim.SetInitTimeStep(4e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-G));
    sim.Initialize();
    sim.DoDynamics(0.45);
    double sum = 0.0;
    for (int i = 0; i < 50; i++) {
        sim.DoDynamics(0.002);
        sum += -floorTracker->ContactForce().z;
    }
    return sum / 50 / (pts.size() * sphereMass(R, DENSITY) * G);
}

}  // namespace

// The meshed box carries the settled bed's weight (1 %), and agrees with the analytical box (2 %).
DEME_BACKEND_TEST(MeshBodies, MeshedBoxCarriesBedWeightLikeAnalyticalBox) {
    const double mesh = floorLoadRatio(true);
    const double analytical = floorLoadRatio(false);
    EXPECT_NEAR(mesh, 1.0, 0.01);
    EXPECT_NEAR(analytical, 1.0, 0.01);
    EXPECT_NEAR(mesh, analytical, 0.02);
}

// A free meshed cube (SetMass) dropped onto the bed comes to rest on it: its velocity vanishes and
// the grains' contact force on it balances its weight (2 %); the floor and the cylinder around the
// bed then carry bed + cube between them (1 %).
DEME_BACKEND_TEST(MeshBodies, FreeCubeSettlesOnBed) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.2, 0.5, 0.02));
    sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.4f);
    sim.InstructBoxDomainBoundingBC("top_open", mat);
    auto floorObj = sim.AddBCPlane(make_float3(0, 0, -0.05f), make_float3(0, 0, 1), mat);
    auto walls = sim.AddExternalObject();
    walls->AddCylinder(make_float3(0), make_float3(0, 0, 1), 0.06f, mat, 0);
    const float a = 0.02f;  // cube half size
    auto cubeMesh = boxMesh(make_float3(-a, -a, -a), make_float3(a, a, a), mat);
    const float cubeMass = 0.2f;
    cubeMesh.SetMass(cubeMass);
    cubeMesh.SetMOI(make_float3(cubeMass * (2 * a) * (2 * a) / 6.f));
    cubeMesh.SetInitPos(make_float3(0, 0, 0.09f));
    auto cube = sim.AddWavefrontMeshObject(cubeMesh);
    std::vector<float3> pts;
    for (const auto& p : bedPoints())
        if (p.x * p.x + p.y * p.y < 0.052f * 0.052f) pts.push_back(p);
    sim.AddClumps(sim.LoadSphereType((float)sphereMass(R, DENSITY), (float)R, mat), pts);
    sim.SetInitTimeStep(4e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-G));
    sim.Initialize();
    auto tc = sim.Track(cube), tf = sim.Track(floorObj), tw = sim.Track(walls);
    EXPECT_TRUE(cube->IsFree());
    sim.DoDynamics(0.8);
    double load = 0.0, floorLoad = 0.0, wallLoad = 0.0;
    for (int i = 0; i < 50; i++) {
        sim.DoDynamics(0.002);
        load += tc->ContactForce().z;
        floorLoad += -tf->ContactForce().z;
        wallLoad += -tw->ContactForce().z;
    }
    const double weight = cubeMass * G;
    EXPECT_LT(tc->Pos().z, 0.05f);   // it fell onto the bed
    EXPECT_GT(tc->Pos().z, -0.03f);  // and did not fall through it
    EXPECT_LT(length(tc->Vel()), 0.01f);
    EXPECT_NEAR(load / 50, weight, 0.02 * weight);
    // At rest the floor and the cylinder carry the weight of the bed and the cube between them
    // (static equilibrium; within 0.15 % in runs whose cube started up to 0.1 mm apart). How it is
    // shared is not fixed: the cylinder is frictional, and its share depends on how the grains
    // settled against it (from -1.7 % to 3.3 % of the weight in those runs, which a check of the
    // floor alone against the whole weight, within 3 %, failed now and then on a GPU, whose runs
    // differ with the order of its atomic sums).
    const double total = weight + pts.size() * sphereMass(R, DENSITY) * G;
    EXPECT_NEAR((floorLoad + wallLoad) / 50, total, 0.01 * total);
    EXPECT_GT(floorLoad / 50, 0.9 * total);  // the floor carries most of it
}

// A vertical blade spinning at +5 rad/s about z through a bed: the grains resist, so the contact
// torque about z reported by the tracker is negative, and ContactAngAccLocal * MOI is that torque.
DEME_BACKEND_TEST(MeshBodies, TorqueOnDrivenBladeOpposesRotation) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.5, 0.02));
    sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.3f);
    sim.InstructBoxDomainBoundingBC("top_open", mat);
    auto drum = sim.AddExternalObject();
    drum->AddCylinder(make_float3(0), make_float3(0, 0, 1), 0.06f, mat, 0);
    sim.AddBCPlane(make_float3(0, 0, -0.05f), make_float3(0, 0, 1), mat);
    auto blade = sim.AddWavefrontMeshObject(
        boxMesh(make_float3(-0.045f, -0.002f, -0.045f), make_float3(0.045f, 0.002f, 0.0f), mat));
    blade->SetFamily(10);
    sim.SetFamilyPrescribedAngVel(10, "0", "0", "5");
    std::vector<float3> pts;
    for (const auto& p : bedPoints())
        if (p.x * p.x + p.y * p.y < 0.052f * 0.052f && std::fabs(p.y) > 0.008f) pts.push_back(p);
    sim.AddClumps(sim.LoadSphereType((float)sphereMass(R, DENSITY), (float)R, mat), pts);
    sim.SetInitTimeStep(4e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-G));
    sim.Initialize();
    auto tb = sim.Track(blade);
    sim.DoDynamics(0.3);
    double torque = 0.0;
    for (int i = 0; i < 100; i++) {
        sim.DoDynamics(0.002);
        torque += tb->ContactTorque().z;
        const float3 viaAcc = tb->ContactAngAccLocal() * tb->MOI();  // the paper's listing
        const float3 local = tb->ContactTorque();                    // rotation about z: local z = global z
        EXPECT_NEAR(viaAcc.z, local.z, 1e-4 * std::fabs(local.z) + 1e-9);
    }
    EXPECT_LT(torque / 100, -1e-4);
    EXPECT_NEAR(tb->AngVelLocal().z, 5.f, 1e-6);
}
