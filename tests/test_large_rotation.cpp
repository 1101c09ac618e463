// Rotations too large for the orientation series (over 0.2 rad in one step) take the exact step,
// which makes the step's midpoint and end angular velocities again from the owner's state at the
// step's start, kept for it (dynamics/OwnerStep.h, finishLargeRotation). Checked through what a
// contact sees of the spin (turned to the global frame where the contact reads it): a sphere
// spinning at 0.3 rad a step about the global y axis, its body frame turned so that its local spin
// axis is x, slides on a frictional floor. Coulomb friction then pushes it along +x at mu g (the
// contact point moves along -x); had the contact read the local spin, it would have pushed it along
// -y. And through the orientation itself: a free sphere spinning so turns by omega t.
#include <gtest/gtest.h>

#include <cmath>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(LargeRotation);

DEME_BACKEND_TEST(LargeRotation, SpinningSphereSlidesAtMuGAlongTheGlobalDirection) {
    constexpr double R = 0.01, MASS = 0.01, MU = 0.5, G = 9.81, DT = 1e-5, T = 0.02;
    constexpr double OMEGA = 3e4;  // 0.3 rad a step: h^2 |w|^2 / 4 = 0.0225, over the series' 0.01
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    sim.InstructBoxDomainDimension(0.2, 0.2, 0.2);
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, MU));
    sim.AddBCPlane(make_float3(0, 0, -0.05f), make_float3(0, 0, 1), mat);
    auto ball = sim.AddClumps(sim.LoadSphereType((float)MASS, (float)R, mat), {make_float3(0, 0, (float)(R - 0.05))});
    // Body frame turned 90 degrees about z: local x is global y.
    ball->SetOriQ(make_float4(0, 0, (float)std::sqrt(0.5), (float)std::sqrt(0.5)));
    ball->SetAngVel(make_float3((float)OMEGA, 0, 0));
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-G));
    sim.SetInitTimeStep(DT);
    sim.SetErrorOutVelocity(1000.f);  // the rim moves at 300 m/s
    sim.SetMaxVelocity(1.f);          // what the centre does; the spin is about the contact's own axis
    sim.Initialize();
    auto tr = sim.Track(ball);
    const float3 w = tr->AngVelGlobal();
    ASSERT_NEAR(w.y, OMEGA, 1e-3 * OMEGA);
    ASSERT_NEAR(w.x, 0.0, 1e-3 * OMEGA);
    sim.DoDynamics(T);
    // Sliding throughout (the rim at 300 m/s, the centre at 0.1): v_x = mu g t, as the normal force
    // averages the weight once the small initial bounce (CoR 0.5) has settled. 3 %: that bounce.
    const float3 v = tr->Vel();
    EXPECT_NEAR(v.x, MU * G * T, 0.03 * MU * G * T);
    EXPECT_NEAR(v.y, 0.0, 0.01 * MU * G * T);
    // The spin is still along global y, slowed by the friction torque mu m g R / (0.4 m R^2) over T:
    // 24.5 rad/s.
    const float3 w1 = tr->AngVelGlobal();
    EXPECT_NEAR(w1.y, OMEGA - MU * G * T / (0.4 * R), 0.1 * MU * G * T / (0.4 * R));
    EXPECT_NEAR(w1.x, 0.0, 1.0);
    EXPECT_NEAR(w1.z, 0.0, 1.0);
}

// A free sphere (no gravity, no contact) spinning at 0.3 rad a step about its body x axis: every
// step is exact, so after n steps its orientation is q0 turned by n h omega about that axis and its
// spin is unchanged. Had a large step kept the start's orientation (no exact step), or its angular
// velocity the start's without the end's being put back, the sphere would not turn or would turn
// otherwise. Tolerance: 100 quaternion products in float, about 1e-5; 1e-4 taken.
DEME_BACKEND_TEST(LargeRotation, FreeSphereTurnsByOmegaTInExactSteps) {
    constexpr double R = 0.01, DT = 1e-5, OMEGA = 3e4;
    constexpr int STEPS = 100;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    sim.InstructBoxDomainDimension(0.2, 0.2, 0.2);
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    auto ball = sim.AddClumps(sim.LoadSphereType(0.01f, (float)R, mat), {make_float3(0, 0, 0)});
    ball->SetAngVel(make_float3((float)OMEGA, 0, 0));
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.SetInitTimeStep(DT);
    sim.SetErrorOutVelocity(1000.f);
    sim.SetMaxVelocity(1.f);
    sim.Initialize();
    auto tr = sim.Track(ball);
    sim.DoDynamics(STEPS * DT);
    const double half = 0.5 * OMEGA * DT * STEPS;  // the turn's half angle: q = (cos, sin x, 0, 0)
    const float4 got = tr->OriQ();                 // (x, y, z, w): the scalar last
    // q and -q are one rotation: compare the one nearer the expected (cos, sin x, 0, 0).
    const double c = std::cos(half), sn = std::sin(half);
    const double sign = got.w * c + got.x * sn >= 0.0 ? 1.0 : -1.0;
    EXPECT_NEAR(sign * got.w, c, 1e-4);
    EXPECT_NEAR(sign * got.x, sn, 1e-4);
    EXPECT_NEAR(got.y, 0.0, 1e-4);
    EXPECT_NEAR(got.z, 0.0, 1e-4);
    const float3 w = tr->AngVelLocal();
    EXPECT_NEAR(w.x, OMEGA, 1e-4 * OMEGA);
    EXPECT_NEAR(w.y, 0.0, 1e-4 * OMEGA);
    EXPECT_NEAR(w.z, 0.0, 1e-4 * OMEGA);
}
