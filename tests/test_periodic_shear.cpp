// A sheared periodic cell (Lees–Edwards, SetPeriodicShear; physics/Periodic.h, docs/periodic.md): a
// grain that leaves through the top enters through the bottom displaced by the offset and slower by
// the shear velocity (its velocity relative to the affine flow unchanged), and a pair touching across
// the z face feels what the same pair feels inside when the inner partner moves as the image does.
// Detection through the displaced images: test_periodic_detection.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(PeriodicShear);

TEST(PeriodicShearInput, NeedsPeriodicXAndZ) {
    DEMSolver w;
    w.SetVerbosity("QUIET");
    auto m = w.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    w.InstructBoxDomainDimension(0.1f, 0.1f, 0.1f);
    w.InstructBoxDomainPeriodicity("xy");
    w.SetPeriodicShear(1.0);
    w.AddClumps(w.LoadSphereType(1e-3f, 0.005f, m), {make_float3(0, 0, 0)});
    w.SetInitTimeStep(1e-5);
    EXPECT_NE(demeErrorMessage([&] { w.Initialize(); }).find("periodic along x and z"), std::string::npos);
    DEMSolver v;
    EXPECT_NE(demeErrorMessage([&] { v.SetPeriodicShear(NAN); }).find("SetPeriodicShear"), std::string::npos);
}

// One grain moving up through the top face at t_c: it enters through the bottom at x less the offset
// rate Lz t_c and with vx less rate Lz; from x0 + vx t before, so after T steps it is at
// x0 + vx T dt - offset(t_c) - rate Lz (T dt - t_c), less whole periods (to 1e-7 m), with vx - rate Lz
// (to 1e-6 m/s): at the face its velocity relative to the affine flow rate z is the same on both sides.
DEME_BACKEND_TEST(PeriodicShear, GrainThroughTheTopEntersDisplacedAndSlower) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    sim.InstructBoxDomainDimension({0.f, 0.1f}, {0.f, 0.1f}, {0.f, 0.1f});
    sim.InstructBoxDomainPeriodicity("xyz");
    const double L = (double)0.1f, dt = 1e-4, rate = 70.0, U = rate * L;
    sim.SetPeriodicShear(rate);
    auto type = sim.LoadSphereType((float)sphereMass(0.005, 2500), 0.005f, mat);
    const float vz = 2.f, vx = 0.3f;
    // Its centre crosses the top face half-way through step 41 (ending at t_c = 41 dt).
    const float z0 = (float)(L - vz * 40.5 * dt), x0 = 0.03f;
    auto grain = sim.AddClumps(type, {make_float3(x0, 0.05f, z0)});
    sim.SetInitTimeStep(dt);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.Initialize();
    auto tr = sim.Track(grain);
    tr->SetVel(make_float3(vx, 0, vz));
    const float z0Now = tr->Pos().z;
    sim.DoDynamics(40 * dt);
    EXPECT_NEAR(tr->Vel().x, vx, 1e-6);  // not yet through
    sim.DoDynamics(60 * dt);
    const double T = 100 * dt, tc = 41 * dt;
    const double offsetAtTc = U * tc - L * std::round(U * tc / L);
    EXPECT_GT(std::fabs(offsetAtTc), 0.01);  // a displacement worth measuring
    const double expectedX = x0 + vx * T - offsetAtTc - U * (T - tc);
    const double dx = tr->Pos().x - expectedX;
    EXPECT_NEAR(dx - L * std::round(dx / L), 0.0, 1e-7);
    EXPECT_NEAR(tr->Pos().z, z0Now + vz * T - L, 1e-7);
    EXPECT_NEAR(tr->Vel().x, vx - U, 1e-6);
    EXPECT_NEAR(tr->Vel().z, vz, 1e-6);
}

// A pair touching across the z face -- A below the top, B above the bottom, so that B's image above,
// displaced by the offset and moving at U more, is where it meets A -- and the same pair inside, with
// the inner B moving at U more: the same forces and velocity changes after a step (to 1e-5). The
// offset is that of t = 0.0123 s (the cell first runs that long with the pairs apart), and the
// tangential force comes mostly from the image's extra U.
DEME_BACKEND_TEST(PeriodicShear, PairAcrossTheZFaceFeelsWhatThePairInsideFeels) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.6, 0.4, 0.05));
    sim.InstructBoxDomainDimension({0.f, 1.f}, {0.f, 1.f}, {0.f, 1.f});
    sim.InstructBoxDomainPeriodicity("xz");
    const double L = 1.0, rate = 0.5, U = rate * L, dt = 1e-5;
    sim.SetPeriodicShear(rate);
    const float r = 0.008f, h = 0.0078125f;  // centre distance 2 h: overlap 0.375 mm
    auto type = sim.LoadSphereType((float)sphereMass(r, 2500), r, mat);
    auto pairs = sim.AddClumps(type, {make_float3(0.1f, 0.2f, 0.2f), make_float3(0.1f, 0.2f, 0.4f),
                                      make_float3(0.6f, 0.7f, 0.2f), make_float3(0.6f, 0.7f, 0.4f)});
    sim.SetInitTimeStep(dt);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.Initialize();
    sim.DoDynamics(1230 * dt);  // at rest and apart: only the offset moves
    const double t = sim.GetSimTime();
    const double offset = U * t - L * std::round(U * t / L);
    ASSERT_GT(std::fabs(offset), 0.005);
    auto tr = sim.Track(pairs);
    // Inside: A (0) below B (1). Across: A (2) under the top face, B (3) above the bottom one at x less
    // the offset, so that its image above is right over A.
    const float xa = 0.5f;
    tr->SetPos(make_float3(0.25f, 0.25f, 0.5f - h), 0);
    tr->SetPos(make_float3(0.25f, 0.25f, 0.5f + h), 1);
    tr->SetPos(make_float3(xa, 0.75f, (float)L - h), 2);
    const double xb = xa - offset;
    tr->SetPos(make_float3((float)(xb - L * std::floor(xb / L)), 0.75f, h), 3);
    const float3 vA = make_float3(0.05f, 0.1f, -0.02f), vB = make_float3(-0.1f, 0.f, 0.01f);
    const float3 vBInside = make_float3(vB.x + (float)U, vB.y, vB.z);
    tr->SetVel(vA, 0);
    tr->SetVel(vBInside, 1);
    tr->SetVel(vA, 2);
    tr->SetVel(vB, 3);
    for (size_t k : {0u, 2u}) tr->SetAngVel(make_float3(4.f, -8.f, 2.f), k);
    for (size_t k : {1u, 3u}) tr->SetAngVel(make_float3(-2.f, 1.f, 16.f), k);
    sim.DoStepDynamics();
    ASSERT_EQ(sim.GetNumContacts(), 2u);
    for (size_t k : {0u, 1u}) {
        const float3 fIn = tr->ContactForce(k), fAcross = tr->ContactForce(k + 2);
        ASSERT_GT(length(fIn), 1.f) << k;
        EXPECT_NEAR(length(fIn - fAcross), 0.0, 1e-5 * length(fIn)) << k;
        EXPECT_NEAR(length(tr->AngVelGlobal(k) - tr->AngVelGlobal(k + 2)), 0.0, 1e-5 * 16) << k;
    }
    // The shear shows in the force: a tangential part along x from the image's extra U.
    EXPECT_GT(std::fabs(tr->ContactForce(2).x), 0.1 * std::fabs(tr->ContactForce(2).z));
    EXPECT_NEAR(length(tr->Vel(0) - tr->Vel(2)), 0.0, 1e-6);
    EXPECT_NEAR(length(tr->Vel(1) - tr->Vel(3) - make_float3((float)U, 0, 0)), 0.0, 1e-6);
}
