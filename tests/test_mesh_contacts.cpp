// Sphere-mesh contacts: a tessellated surface must act like the smooth surface it represents.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "BackendFixture.h"
#include "MeshBuilders.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(MeshContact);

namespace {

constexpr double R = 0.01, DENSITY = 2600, G = 9.81;

// Drops a ball from 5 cm onto the floor z = 0 (a mesh of 2 mm cells, or an analytical plane) at
// (x, y) and returns the height of the first rebound's apex.
double reboundApex(bool meshFloor, float x, float y) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e8, 0.3, 0.5, 0.3));
    sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.2f);
    if (meshFloor)
        sim.AddWavefrontMeshObject(gridFloor(-0.02f, -0.02f, 0.f, 20, 0.002f, mat));
    else
        sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    auto ball = sim.AddClumps(sim.LoadSphereType((float)sphereMass(R, DENSITY), (float)R, mat),
                              {make_float3(x, y, (float)(R + 0.05))});
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-G));
    sim.SetInitTimeStep(2e-6);
    sim.Initialize();
    auto tr = sim.Track(ball);
    bool bounced = false;
    double apex = 0.0;
    for (int i = 0; i < 200000; i++) {
        sim.DoStepDynamics();
        const float vz = tr->Vel().z;
        if (!bounced && vz > 0.f) bounced = true;
        if (bounced && vz <= 0.f) {
            apex = tr->Pos().z - R;
            break;
        }
    }
    return apex;
}

}  // namespace

// Reference: the same drop on the analytical plane. The rebound apex on the mesh must match it
// within 1 % whether the ball lands inside a triangle, on an edge or on a vertex (where 2 or 8
// triangles meet): one contact, with the plane's normal and overlap.
DEME_BACKEND_TEST(MeshContact, DropOnTessellatedFloorBouncesLikeThePlane) {
    const double plane = reboundApex(false, 0.f, 0.f);
    ASSERT_GT(plane, 0.005);  // CoR 0.5: about 0.05 * 0.25
    EXPECT_NEAR(reboundApex(true, 0.0007f, 0.0003f), plane, 0.01 * plane) << "face";
    EXPECT_NEAR(reboundApex(true, 0.002f, 0.0011f), plane, 0.01 * plane) << "edge";
    EXPECT_NEAR(reboundApex(true, 0.001f, 0.001f), plane, 0.01 * plane) << "diagonal edge";
    EXPECT_NEAR(reboundApex(true, 0.002f, 0.002f), plane, 0.01 * plane) << "vertex";
}

// A ball rolling at 0.3 m/s over the tessellated floor crosses an edge every few hundred steps;
// the normal force stays within 2 % of its weight throughout (no spikes, no doubled force).
DEME_BACKEND_TEST(MeshContact, RollingAcrossEdgesKeepsNormalForceSmooth) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e8, 0.3, 0.2, 0.5));
    sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.2f);
    auto floorMesh = sim.AddWavefrontMeshObject(gridFloor(-0.05f, -0.05f, 0.f, 50, 0.002f, mat));
    const double m = sphereMass(R, DENSITY);
    const double Estar = effectiveModulus(1e8, 0.3);
    const double overlap = std::pow(m * G / (4.0 / 3.0 * Estar * std::sqrt(R)), 2.0 / 3.0);
    auto ball = sim.AddClumps(sim.LoadSphereType((float)m, (float)R, mat),
                              {make_float3(-0.03f, 0.0013f, (float)(R - overlap))});
    const float v = 0.3f;
    ball->SetVel(make_float3(v, 0, 0));
    ball->SetAngVel(make_float3(0, (float)(v / R), 0));  // rolling without slip
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-G));
    sim.SetInitTimeStep(2e-6);
    sim.Initialize();
    auto tf = sim.Track(floorMesh), tb = sim.Track(ball);
    sim.DoDynamics(0.01);  // let the start-up transient pass
    double worst = 0.0;
    const float x0 = tb->Pos().x;
    for (int i = 0; i < 50000; i++) {
        sim.DoStepDynamics();
        worst = std::max(worst, std::fabs(-tf->ContactForce().z - m * G) / (m * G));
    }
    EXPECT_GT(tb->Pos().x - x0, 0.025f);  // crossed a dozen cells, each with 2-3 edges on the path
    EXPECT_LT(worst, 0.02);
}

// A ball resting in a meshed, frictionless V-groove with 45-degree faces touches both faces; each
// normal force is m g / (2 cos 45) and together they carry its weight (1 %). (With friction the
// split between normal and friction forces depends on how the ball settled.)
DEME_BACKEND_TEST(MeshContact, BallInVGrooveBalancesWeight) {
    const std::string dir = scratchDir().string();
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e8, 0.3, 0.2, 0.0));
    sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.2f);
    // Faces z = |x| for |x| <= 0.03, each as 4 x 6 cells along y.
    std::vector<float3> v;
    std::vector<int3> f;
    const int ny = 6;
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= 4; i++) {
            const float x = -0.03f + 0.015f * i;
            v.push_back(make_float3(x, -0.03f + 0.01f * j, std::fabs(x)));
        }
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < 4; i++) {
            const int a = j * 5 + i, b = a + 1, c = a + 6, d = a + 5;
            f.push_back(make_int3(a, b, c));
            f.push_back(make_int3(a, c, d));
        }
    auto groove = sim.AddWavefrontMeshObject(DEMMeshConnected(v, f, mat));
    const double m = sphereMass(R, DENSITY);
    auto ball = sim.AddClumps(sim.LoadSphereType((float)m, (float)R, mat),
                              {make_float3(0, 0.0012f, (float)(R * std::sqrt(2.0)))});
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-G));
    sim.SetInitTimeStep(2e-6);
    sim.Initialize();
    auto tg = sim.Track(groove);
    sim.DoDynamics(0.2);
    EXPECT_NEAR(-tg->ContactForce().z, m * G, 0.01 * m * G);
    sim.WriteContactFile(dir + "/c.csv");
    sim.FlushOutput();  // files are written in the background
    std::ifstream in(dir + "/c.csv");
    std::string line;
    std::getline(in, line);
    int n = 0;
    while (std::getline(in, line)) {
        std::vector<double> col;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) col.push_back(cell == "SM" ? 0.0 : std::stod(cell));
        const double fn = col[8] * col[11] + col[9] * col[12] + col[10] * col[13];  // f . n
        EXPECT_NEAR(fn, m * G / (2.0 * std::cos(deme::PI / 4)), 0.01 * m * G) << line;
        n++;
    }
    EXPECT_EQ(n, 2);
}
