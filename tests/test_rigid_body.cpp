// Rigid-body integration of clumps: torque-free tumbling, fixed and prescribed families.
#include <gtest/gtest.h>

#include <cmath>

#include "BackendFixture.h"
#include "TestHelpers.h"
#include "physics/Quaternion.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(RigidBody);
DEME_BACKEND_TEST_SUITE(Families);
DEME_BACKEND_TEST_SUITE(TimeStepping);

// A free clump with three distinct principal moments, spinning about a general axis with no
// gravity and no contacts (Euler's torque-free motion): the angular momentum vector in the global
// frame, L = R(q) I w, and the kinetic energy 1/2 w.Iw are invariants of the exact motion.
// Tolerance 1e-4 relative over one second (1e4 steps), the requirement.
DEME_BACKEND_TEST(RigidBody, TorqueFreeClumpConservesAngularMomentumAndEnergy) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e8, 0.3, 0.5, 0.5));
    sim.InstructBoxDomainDimension(1, 1, 1);
    // The paper's 3-sphere clump (3_clump.csv) with its principal moments, scaled to r = 0.01.
    auto tmpl = sim.LoadClumpType(
        2600.f * 5.5886717f, make_float3(2.928f, 2.6029f, 3.9908f) * 2600.f, {0.8f, 0.8f, 0.8f},
        {make_float3(0.5f, 0.341729f, 0), make_float3(0, -0.658271f, 0), make_float3(-0.5f, 0.341729f, 0)}, mat);
    tmpl->Scale(0.01f);
    auto clump = sim.AddClumps(tmpl, {make_float3(0, 0, 0)});
    clump->SetAngVel(make_float3(3.f, 0.5f, 1.f));  // mostly about the intermediate axis: it tumbles
    sim.SetInitTimeStep(1e-4);
    sim.Initialize();
    auto tr = sim.Track(clump);
    const float3 I = tr->MOI();
    auto invariants = [&](double3& L, double& E) {
        const float3 w = tr->AngVelLocal();
        const float3 Lg = rotateToGlobal(tr->OriQ(), w * I);
        L = to_double3(Lg);
        E = 0.5 * ((double)I.x * w.x * w.x + (double)I.y * w.y * w.y + (double)I.z * w.z * w.z);
    };
    double3 L0;
    double E0;
    invariants(L0, E0);
    double maxLErr = 0.0, maxEErr = 0.0;
    float3 w0 = tr->AngVelLocal();
    bool tumbled = false;
    for (int frame = 0; frame < 100; frame++) {
        sim.DoDynamics(0.01);
        double3 L;
        double E;
        invariants(L, E);
        maxLErr = std::max(maxLErr, length(L - L0) / length(L0));
        maxEErr = std::max(maxEErr, std::fabs(E - E0) / E0);
        if (length(tr->AngVelLocal() - w0) > 0.5f) tumbled = true;
    }
    EXPECT_NEAR(sim.GetSimTime(), 1.0, 1e-9);
    EXPECT_TRUE(tumbled) << "the body-frame angular velocity should change: the test must exercise gyroscopic terms";
    EXPECT_LT(maxLErr, 1e-4);
    EXPECT_LT(maxEErr, 1e-4);
    EXPECT_LT(length(tr->Vel()), 1e-9);
}

// A fixed family never moves, even under gravity and contact; a family with prescribed angular
// velocity w about z has turned by exactly w t; prescribed linear velocity moves by v t.
DEME_BACKEND_TEST(Families, FixedStaysAndPrescribedMotionFollowsItsExpression) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    sim.InstructBoxDomainDimension(4, 4, 4);
    auto tmpl = sim.LoadSphereType(1.f, 0.05f, mat);
    auto fixedBall = sim.AddClumps(tmpl, {make_float3(0, 0, -0.5f)});
    fixedBall->SetFamily(1);
    // Resting on the fixed ball, pressing on it under gravity.
    auto onTop = sim.AddClumps(tmpl, {make_float3(0, 0, -0.401f)});
    auto spinner = sim.AddClumps(tmpl, {make_float3(0.5f, 0.5f, 0.5f)});
    spinner->SetFamily(2);
    auto mover = sim.AddClumps(tmpl, {make_float3(-0.5f, 0, 0)});
    mover->SetFamily(3);
    sim.SetFamilyFixed(1);
    const double w = 2.0;
    sim.SetFamilyPrescribedAngVel(2, "0", "0", "2.0");
    sim.SetFamilyPrescribedLinVel(2, "0", "0", "0");
    sim.SetFamilyPrescribedLinVel(3, "0.1*cos(t)", "0", "none");  // x(t) = x0 + 0.1 sin(t); z free (falls)
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetInitTimeStep(1e-4);
    sim.Initialize();
    auto tf = sim.Track(fixedBall), ts = sim.Track(spinner), tm = sim.Track(mover), tt = sim.Track(onTop);
    const float3 p0 = tf->Pos();
    sim.DoDynamics(0.5);
    EXPECT_EQ(tf->Pos().x, p0.x);
    EXPECT_EQ(tf->Pos().y, p0.y);
    EXPECT_EQ(tf->Pos().z, p0.z);
    EXPECT_EQ(length(tf->Vel()), 0.f);
    EXPECT_GT(length(tf->ContactForce()), 1.f);  // it was pushed on, and did not move
    EXPECT_NEAR(tt->Pos().z, -0.401, 0.01);      // and the ball on top is held up
    // Turned angle from the quaternion about z: q = (cos(theta/2), 0, 0, sin(theta/2)).
    const float4 q = ts->OriQ();
    const double theta = 2.0 * std::atan2((double)q.z, (double)q.w);
    const double expected = std::remainder(w * sim.GetSimTime(), 2.0 * deme::PI);
    EXPECT_NEAR(std::remainder(theta - expected, 2.0 * deme::PI), 0.0, 1e-5);
    EXPECT_NEAR(ts->Pos().z, 0.5, 1e-6);  // gravity does not act on prescribed components
    // x(t) = -0.5 + 0.1 sin(t); first-order integration of the evaluated velocity, dt = 1e-4.
    EXPECT_NEAR(tm->Pos().x, -0.5 + 0.1 * std::sin(sim.GetSimTime()), 1e-5);
    EXPECT_LT(tm->Pos().z, -0.5);  // the free component fell: z = -g t^2 / 2 = -1.226
}

// UpdateStepSize between DoDynamics calls: a free fall of 0.2 s at dt = 1e-3 then 0.2 s at 1e-4 ends
// where z = z0 - g t^2 / 2 puts it (exact for constant acceleration up to the integrator's first-order
// position error, g dt t / 2 <= 1e-3 m at the coarse step) and the clock counts both phases' steps.
DEME_BACKEND_TEST(TimeStepping, UpdateStepSizeBetweenCalls) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    sim.InstructBoxDomainDimension(4, 4, 4);
    auto ball = sim.AddClumps(sim.LoadSphereType(1.f, 0.05f, mat), {make_float3(0, 0, 1.5f)});
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetInitTimeStep(1e-3);
    sim.Initialize();
    auto t = sim.Track(ball);
    sim.DoDynamics(0.2);
    EXPECT_EQ(sim.GetTimeStep(), 1e-3);
    sim.UpdateStepSize(1e-4);
    EXPECT_EQ(sim.GetTimeStep(), 1e-4);
    sim.DoDynamics(0.2);
    EXPECT_NEAR(sim.GetSimTime(), 0.4, 1e-9);
    // Velocities are floats: 2200 additions of g dt near 4 m/s round by up to 2.4e-7 each (5e-4 in all),
    // still half of what one step too many at the fine step (9.8e-4) would add.
    EXPECT_NEAR(t->Vel().z, -9.81 * 0.4, 5e-4);
    EXPECT_NEAR(t->Pos().z, 1.5 - 0.5 * 9.81 * 0.4 * 0.4, 1.5e-3);
    EXPECT_THROW(sim.UpdateStepSize(0.0), deme::Error);
    EXPECT_THROW(sim.UpdateStepSize(-1e-4), deme::Error);
}
