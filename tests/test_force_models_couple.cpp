// A custom force model's pure couple (`couple_torque`): the torque it names acts on A, its opposite on
// B, and no force on either; checked against rigid-body dynamics on both backends.
#include <gtest/gtest.h>

#include <cmath>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(ForceModelCouple);

namespace {

// A constant couple about global z while the spheres overlap; no force, so they stay where they are.
const char* kConstantCouple =
    "if (overlapDepth > 0.0) couple_torque = make_float3(0.f, 0.f, tau[bodyAMatType]);\n";

}  // namespace

// Two spheres of different sizes and masses, overlapping by 0.1 mm, no gravity, a couple of
// tau = 2e-4 N m for t = 0.05 s. Rigid-body dynamics: omega_z = +tau t / I_A and -tau t / I_B
// (I = 2/5 m R^2), the angular momenta equal and opposite (the couple adds none to the pair), the
// centres unmoved. The owners' spins are integrated in float over 5,000 steps: 1e-4 relative.
DEME_BACKEND_TEST(ForceModelCouple, CoupleTurnsTheOwnersOppositely) {
    const double RA = 0.01, RB = 0.006, mA = 0.02, mB = 0.005, tau = 2e-4, dt = 1e-5, t = 0.05;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial({{"E", 1e7}, {"nu", 0.3}, {"CoR", 0.5}, {"tau", tau}});
    auto model = sim.DefineContactForceModel(kConstantCouple);
    model->SetMustHaveMatProp({"tau"});
    sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.1f);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    const float gap = (float)(RA + RB - 1e-4);
    auto a = sim.AddClumps(sim.LoadSphereType((float)mA, (float)RA, mat), {make_float3(0, 0, 0)});
    auto b = sim.AddClumps(sim.LoadSphereType((float)mB, (float)RB, mat), {make_float3(gap, 0, 0)});
    sim.SetInitTimeStep(dt);
    sim.Initialize();
    auto ta = sim.Track(a);
    auto tb = sim.Track(b);
    sim.DoDynamics(t);
    const double IA = 0.4 * mA * RA * RA, IB = 0.4 * mB * RB * RB;
    const float3 wA = ta->AngVelGlobal(), wB = tb->AngVelGlobal();
    std::cout << "[  couple  ] omega_z A " << wA.z << " (theory " << tau * t / IA << "), B " << wB.z << " (theory "
              << -tau * t / IB << ")" << std::endl;
    EXPECT_NEAR(wA.z, tau * t / IA, 1e-4 * tau * t / IA);
    EXPECT_NEAR(wB.z, -tau * t / IB, 1e-4 * tau * t / IB);
    EXPECT_NEAR(IA * wA.z + IB * wB.z, 0.0, 1e-4 * tau * t);
    EXPECT_NEAR(std::hypot(wA.x, wA.y) + std::hypot(wB.x, wB.y), 0.0, 1e-6 * tau * t / IB);
    EXPECT_NEAR(length(ta->Pos() - make_float3(0, 0, 0)), 0.0, 1e-9);
    EXPECT_NEAR(length(tb->Pos() - make_float3(gap, 0, 0)), 0.0, 1e-9);
    EXPECT_NEAR(length(ta->Vel()) + length(tb->Vel()), 0.0, 1e-9);
}
