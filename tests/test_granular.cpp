// Many-body validation: a settled bed's floor force, an elastic gas's energy, static friction.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(SettledBed);
DEME_BACKEND_TEST_SUITE(ElasticGas);
DEME_BACKEND_TEST_SUITE(StaticFriction);

// 1331 spheres settle in a walled box. At rest the bed is in static equilibrium: with frictionless
// side walls (which then carry no vertical load) the floor carries the bed's whole weight (1 %).
DEME_BACKEND_TEST(SettledBed, FloorForceEqualsWeight) {
    const double r = 0.005, density = 2600;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto grain = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.5, 0.02));
    auto side = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.0));
    sim.SetMaterialPropertyPair("mu", grain, side, 0.0);
    sim.SetMaterialPropertyPair("Crr", grain, side, 0.0);
    sim.InstructBoxDomainDimension(0.12f, 0.12f, 0.4f);
    auto walls = sim.AddExternalObject();
    walls->AddPlane(make_float3(-0.06f, 0, 0), make_float3(1, 0, 0), side);
    walls->AddPlane(make_float3(0.06f, 0, 0), make_float3(-1, 0, 0), side);
    walls->AddPlane(make_float3(0, -0.06f, 0), make_float3(0, 1, 0), side);
    walls->AddPlane(make_float3(0, 0.06f, 0), make_float3(0, -1, 0), side);
    auto floorObj = sim.AddBCPlane(make_float3(0, 0, -0.15f), make_float3(0, 0, 1), grain);
    auto tmpl = sim.LoadSphereType((float)sphereMass(r, density), (float)r, grain);
    // A jittered grid, so that the bed does not stay a perfect lattice.
    std::vector<float3> pts =
        GridSampler(2.2f * (float)r).SampleBox(make_float3(0, 0, -0.05f), make_float3(0.05f, 0.05f, 0.05f));
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> jitter(-0.05f * (float)r, 0.05f * (float)r);
    for (auto& p : pts) p = p + make_float3(jitter(rng), jitter(rng), jitter(rng));
    ASSERT_GE(pts.size(), 1000u);
    sim.AddClumps(tmpl, pts);
    sim.SetInitTimeStep(4e-5);  // ~10 % of the Rayleigh time step
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.Initialize();
    auto tr = sim.Track(floorObj);
    auto ke = sim.CreateInspector("clump_kinetic_energy");
    sim.DoDynamics(0.4);
    // Average over a window to remove the residual elastic ringing.
    double sum = 0.0;
    const int n = 50;
    for (int i = 0; i < n; i++) {
        sim.DoDynamics(0.002);
        sum += -tr->ContactForce().z;  // force on the floor from the grains points down
    }
    const double weight = pts.size() * sphereMass(r, density) * 9.81;
    EXPECT_NEAR(sum / n, weight, 0.01 * weight);
    // Settled: the rms speed is small (a few surface grains may still creep along the walls).
    const double rms = std::sqrt(2.0 * ke->GetValue() / (pts.size() * sphereMass(r, density)));
    EXPECT_LT(rms, 0.02);
}

// Frictionless, perfectly elastic spheres in a closed box with no gravity: the Hertz spring is
// conservative, so kinetic energy before and after 10^4 steps agrees to 1 % (the bound),
// sampled at moments when few contacts are active.
DEME_BACKEND_TEST(ElasticGas, KineticEnergyDriftBelowOnePercent) {
    const double r = 0.005, density = 2600;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e9, 0.3, 1.0, 0.0));
    sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.1f);
    sim.InstructBoxDomainBoundingBC("all", mat);
    auto tmpl = sim.LoadSphereType((float)sphereMass(r, density), (float)r, mat);
    std::vector<float3> pts = GridSampler(0.02f).SampleBox(make_float3(0, 0, 0), make_float3(0.04f, 0.04f, 0.04f));
    auto gas = sim.AddClumps(tmpl, pts);
    std::mt19937 rng(7);
    std::normal_distribution<float> vel(0.f, 1.f);
    std::vector<float3> v(pts.size());
    for (auto& x : v) x = make_float3(vel(rng), vel(rng), vel(rng));
    gas->SetVel(v);
    // About 75 steps per collision (Hertz contact time ~1.5e-4 s at these speeds).
    sim.SetInitTimeStep(2e-6);
    sim.Initialize();
    auto ke = sim.CreateInspector("clump_kinetic_energy");
    const double e0 = ke->GetValue();
    for (int i = 0; i < 10000; i++) sim.DoStepDynamics();
    // Step on until no pair is in contact, so no energy is parked in springs.
    int extra = 0;
    while (sim.GetNumContacts() > 0 && extra < 5000) {
        sim.DoStepDynamics();
        extra++;
    }
    ASSERT_EQ(sim.GetNumContacts(), 0u);
    EXPECT_NEAR(ke->GetValue(), e0, 0.01 * e0);
    // The gas did collide: the velocities changed.
    auto tr = sim.Track(gas);
    double changed = 0.0;
    for (size_t i = 0; i < pts.size(); i++) changed += length(tr->Vel(i) - v[i]);
    EXPECT_GT(changed / pts.size(), 0.5);
}

// Static friction: a flat 3-sphere clump (it cannot roll) resting on a 20 degree slope with
// mu = 0.5 > tan(20 deg) = 0.364 sticks. After settling into its elastic equilibrium it drifts
// less than 1e-6 m over one second.
DEME_BACKEND_TEST(StaticFriction, ClumpSticksOnSlopeBelowFrictionAngle) {
    const double alpha = 20.0 * deme::PI / 180.0, g = 9.81;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.5));
    sim.InstructBoxDomainDimension(1, 1, 1);
    sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    const float rs = 0.01f;
    const float m = 3.f * (float)sphereMass(rs, 2600);
    // Three spheres in a triangle in the xy plane; moments of the triangle of point masses plus spheres.
    const float d = 0.015f;
    std::vector<float3> pos = {make_float3(d, 0, 0), make_float3(-0.5f * d, 0.866f * d, 0),
                               make_float3(-0.5f * d, -0.866f * d, 0)};
    const float Ixy = m / 3.f * (1.5f * d * d) + 3.f * 0.4f * (m / 3.f) * rs * rs;
    auto tmpl = sim.LoadClumpType(
        m, make_float3(Ixy, Ixy, 2.f * Ixy - 3.f * 0.4f * (m / 3.f) * rs * rs + 0.8f * m * rs * rs / 1.f),
        std::vector<float>(3, rs), pos, mat);
    auto clump = sim.AddClumps(tmpl, {make_float3(0, 0, rs)});
    sim.SetInitTimeStep(1e-5);
    sim.SetGravitationalAcceleration(make_float3((float)(-g * std::sin(alpha)), 0, (float)(-g * std::cos(alpha))));
    sim.Initialize();
    auto tr = sim.Track(clump);
    sim.DoDynamics(0.3);  // settle: normal and tangential springs take up the load
    const float3 p0 = tr->Pos();
    sim.DoDynamics(1.0);
    const float3 p1 = tr->Pos();
    EXPECT_LT(length(p1 - p0), 1e-6f);
    EXPECT_GT(sim.GetNumContacts(), 2u);  // all three spheres on the slope
}
