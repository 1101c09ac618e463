// Validation of the default Hertz-Mindlin model on single impacts, against closed-form answers.
#include <gtest/gtest.h>

#include <vector>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(HertzImpact);
DEME_BACKEND_TEST_SUITE(HeadOnCollision);

namespace {

struct ImpactResult {
    double contactDuration = 0.0;
    double maxOverlap = 0.0;
    double reboundSpeed = 0.0;
};

// A sphere falls (no gravity) at `speed` onto the plane z = 0 and bounces off.
ImpactResult dropOnPlane(double r, double density, double E, double nu, double CoR, double speed, double dt) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(E, nu, CoR, 0.0));
    sim.InstructBoxDomainDimension(1, 1, 1);
    auto floor = sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    auto tmpl = sim.LoadSphereType((float)sphereMass(r, density), (float)r, mat);
    const double z0 = r + 0.5 * speed * 20 * dt;  // reaches the plane after ~10 steps
    auto ball = sim.AddClumps(tmpl, {make_float3(0, 0, (float)z0)});
    ball->SetVel(make_float3(0, 0, (float)-speed));
    sim.SetInitTimeStep(dt);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.Initialize();
    auto tr = sim.Track(ball);
    ImpactResult res;
    bool touched = false;
    for (int step = 0; step < 200000; step++) {
        sim.DoStepDynamics();
        const double overlap = r - tr->Pos().z;
        if (overlap > 0) {
            touched = true;
            res.contactDuration += dt;
            res.maxOverlap = std::max(res.maxOverlap, overlap);
        } else if (touched) {
            res.reboundSpeed = tr->Vel().z;
            break;
        }
    }
    return res;
}

}  // namespace

// Hertz theory (Johnson, Contact Mechanics, 1985, §11.1): a sphere of mass m and radius R hitting a
// rigid-like flat of effective modulus E* at speed v reaches
//   delta_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5),  and stays in contact for t_c = 2.9432 delta_max / v.
// With CoR = 1 the model has no damping; tolerance 2 % (the requirement).
DEME_BACKEND_TEST(HertzImpact, DurationAndPeakOverlapMatchTheory) {
    const double r = 0.01, density = 2600, E = 1e8, nu = 0.3, v = 1.0;
    const double m = sphereMass(r, density);
    const double Estar = effectiveModulus(E, nu);
    const double deltaMax = std::pow(15.0 * m * v * v / (16.0 * Estar * std::sqrt(r)), 0.4);
    const double tc = 2.9432 * deltaMax / v;
    const ImpactResult res = dropOnPlane(r, density, E, nu, 1.0, v, tc / 2000);
    EXPECT_NEAR(res.maxOverlap, deltaMax, 0.02 * deltaMax);
    EXPECT_NEAR(res.contactDuration, tc, 0.02 * tc);
    EXPECT_NEAR(res.reboundSpeed, v, 0.02 * v);  // elastic: the speed comes back
}

// The damping coefficient is derived from CoR so that rebound speed / impact speed = CoR
// (paper §3.1); tolerance 5 % (the requirement).
DEME_BACKEND_TEST(HertzImpact, RestitutionMatchesCoR) {
    const double r = 0.01, density = 2600, E = 1e8, nu = 0.3, v = 1.0;
    const double m = sphereMass(r, density);
    const double deltaMax = std::pow(15.0 * m * v * v / (16.0 * effectiveModulus(E, nu) * std::sqrt(r)), 0.4);
    const double dt = 2.9432 * deltaMax / v / 2000;
    for (double cor : {0.2, 0.5, 0.8}) {
        const ImpactResult res = dropOnPlane(r, density, E, nu, cor, v, dt);
        EXPECT_NEAR(res.reboundSpeed / v, cor, 0.05 * cor) << "CoR " << cor;
    }
}

// Two equal spheres meeting head-on, in a frame where the pair drifts: the total momentum is
// conserved to 1e-6 relative, and in the centre-of-mass frame the two move as mirror images.
DEME_BACKEND_TEST(HeadOnCollision, MomentumConservedAndSymmetric) {
    const double r = 0.01, density = 2600, dt = 1e-6;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e8, 0.3, 0.5, 0.3));
    sim.InstructBoxDomainDimension(1, 1, 1);
    auto tmpl = sim.LoadSphereType((float)sphereMass(r, density), (float)r, mat);
    auto pair = sim.AddClumps(tmpl, {make_float3(-0.0105f, 0, 0), make_float3(0.0105f, 0, 0)});
    const float vA = 1.5f, vB = -0.5f;  // centre of mass moves at +0.5 m/s
    pair->SetVel(std::vector<float3>{make_float3(vA, 0, 0), make_float3(vB, 0, 0)});
    sim.SetInitTimeStep(dt);
    sim.Initialize();
    auto tr = sim.Track(pair);
    const double p0 = (double)vA + (double)vB;
    double maxErr = 0.0;
    bool collided = false;
    for (int i = 0; i < 3000; i++) {
        sim.DoStepDynamics();
        const double p = (double)tr->Vel(0).x + (double)tr->Vel(1).x;
        maxErr = std::max(maxErr, std::fabs(p - p0) / std::fabs(p0));
        if (sim.GetNumContacts() > 0) collided = true;
        // Mirror symmetry about the centre of mass, which moves at (vA + vB)/2.
        const double vcm = 0.5 * p;
        EXPECT_NEAR(tr->Vel(0).x - vcm, -(tr->Vel(1).x - vcm), 1e-6);
        EXPECT_NEAR(tr->Vel(0).y, 0.0, 1e-9);
    }
    EXPECT_TRUE(collided);
    EXPECT_LT(maxErr, 1e-6);
    // They separated: A now moves slower than B.
    EXPECT_LT(tr->Vel(0).x, tr->Vel(1).x);
}
