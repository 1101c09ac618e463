// Bad input found while a simulation runs, on every backend (each has its own step loop and fault
// checks): divergence and leaving the domain are a deme::Error naming the owner, and a rejected
// prescription changes nothing (on the GPU prescriptions are compiled into a kernel). Checks and the
// minimal scene: BadInputChecks.h; input rejected before a simulation starts: test_bad_input.cpp.
#include <deme/deme.h>
#include <gtest/gtest.h>

#include "BackendFixture.h"
#include "BadInputChecks.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(BadInputInRun);

namespace {

// Two stiff, light spheres (E = 1e9 Pa, m = 1 g, r = 0.01 m), centres `gap` apart along z, with an
// error-out velocity of 1 m/s.
void twoStiffSpheres(DEMSolver& sim, float gap) {
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial({{"E", 1e9}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}});
    sim.InstructBoxDomainDimension(1, 1, 1);
    auto t = sim.LoadSphereType(1e-3f, 0.01f, mat);
    sim.AddClumps(t, {make_float3(0, 0, 0), make_float3(0, 0, gap)});
    sim.SetInitTimeStep(1e-5);
    sim.SetErrorOutVelocity(1.0f);
    sim.Initialize();
}

}  // namespace

DEME_BACKEND_TEST(BadInputInRun, DivergenceNamesOwner) {
    // Placed with half a radius of overlap: Hertz gives F ~ 4/3 * E/(2(1-nu^2)) * sqrt(r/2) *
    // delta^1.5 ~ 5e4 N, i.e. ~0.5 m/s gained in the first 1e-5 s step, so they pass 1 m/s within a
    // few steps.
    DEMSolver sim;
    twoStiffSpheres(sim, 0.015f);
    EXPECT_DEME_ERROR([&] { sim.DoDynamics(1e-3); }, {"DoDynamics", "owner", "SetErrorOutVelocity"});
}

DEME_BACKEND_TEST(BadInputInRun, NoDivergenceWithoutOverlap) {
    // Control for the test above: the same spheres apart stay below 1 m/s and run without error.
    DEMSolver sim;
    twoStiffSpheres(sim, 0.05f);
    EXPECT_NO_THROW(sim.DoDynamics(1e-3));
}

// A bad expression in any component leaves the family's prescription untouched.
DEME_BACKEND_TEST(BadInputInRun, FailedPrescriptionChangesNothing) {
    Scene1 s;
    s.batch->SetFamily(1);
    EXPECT_DEME_ERROR([&] { s.sim.SetFamilyPrescribedLinVel(1, "1", "0.1*sin(", "none"); },
                      {"SetFamilyPrescribedLinVel"});
    s.sim.Initialize();
    s.sim.DoDynamics(0.01);
    auto tr = s.sim.Track(s.batch);
    EXPECT_EQ(tr->Vel().x, 0.f);
}

// The domain is the box the user gave, also along its short axes (not just the encodable range).
DEME_BACKEND_TEST(BadInputInRun, LeavingAFlatDomainUpwardsIsAnError) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    sim.InstructBoxDomainDimension(1, 1, 0.1f);
    auto b = sim.AddClumps(sim.LoadSphereType(1.f, 0.01f, mat), {make_float3(0, 0, 0)});
    b->SetVel(make_float3(0, 0, 1));
    sim.SetInitTimeStep(1e-4);
    sim.Initialize();
    EXPECT_DEME_ERROR([&] { sim.DoDynamics(0.3); }, {"DoDynamics", "owner 0", "left the simulation domain"});
}
