// Rotations too large for the orientation series (over 0.2 rad in one step) take the exact step,
// which reads the owner's midpoint angular velocity from its cache slot and then puts the global
// angular velocity there (dynamics/OwnerStep.h, finishLargeRotation). Checked through what a contact
// sees of that slot: a sphere spinning at 0.3 rad a step about the global y axis, its body frame
// turned so that its local spin axis is x, slides on a frictional floor. Coulomb friction then
// pushes it along +x at mu g (the contact point moves along -x); had the contact read the local
// spin, it would have pushed it along -y.
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
