// Periodic boundaries (InstructBoxDomainPeriodicity, physics/Periodic.h, docs/periodic.md): grains
// that cross a periodic face keep their motion, pairs across a face feel what the same pair feels
// inside, and an elastic gas in a fully periodic box keeps its energy and momentum. Detection
// against a minimum-image brute force: test_periodic_detection.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(Periodic);

namespace {

bool same(const float3& a, const float3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// The message of Initialize's deme::Error for a box of `size` periodic along `axes`, holding one
// sphere of radius r at its centre, after `addMore(solver, material)` added walls.
template <class AddMore>
std::string initializeError(const float3& size, const std::string& axes, float r, AddMore addMore) {
    DEMSolver w;
    w.SetVerbosity("QUIET");
    auto m = w.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    w.InstructBoxDomainDimension(size.x, size.y, size.z);
    w.InstructBoxDomainPeriodicity(axes);
    addMore(w, m);
    w.AddClumps(w.LoadSphereType(1e-3f, r, m), {make_float3(0, 0, 0)});
    w.SetInitTimeStep(1e-5);
    return demeErrorMessage([&] { w.Initialize(); });
}

}  // namespace

TEST(Periodicity, BadInputIsAnErrorNamingTheCall) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    EXPECT_NE(demeErrorMessage([&] { sim.InstructBoxDomainPeriodicity("xw"); }).find("InstructBoxDomainPeriodicity"),
              std::string::npos);
    EXPECT_NE(demeErrorMessage([&] { sim.InstructBoxDomainPeriodicity("xx"); }).find("twice"), std::string::npos);
    sim.InstructBoxDomainPeriodicity("");  // none: fine
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    auto type = sim.LoadSphereType(1e-3f, 0.005f, mat);

    // Walls on periodic faces.
    {
        const std::string msg = initializeError({0.1f, 0.1f, 0.1f}, "x", 0.005f, [](DEMSolver& w, auto m) {
            w.InstructBoxDomainBoundingBC("all", m);
        });
        EXPECT_NE(msg.find("Initialize"), std::string::npos) << msg;
        EXPECT_NE(msg.find("periodic x axis"), std::string::npos) << msg;
        EXPECT_NE(msg.find("periodic face"), std::string::npos) << msg;
    }
    // A cylinder across the periodic axis.
    {
        const std::string msg = initializeError({0.1f, 0.1f, 0.1f}, "y", 0.005f, [](DEMSolver& w, auto m) {
            w.AddExternalObject()->AddCylinder(make_float3(0), make_float3(1, 0, 0), 0.04f, m, 0);
        });
        EXPECT_NE(msg.find("cylinder"), std::string::npos) << msg;
        EXPECT_NE(msg.find("periodic y axis"), std::string::npos) << msg;
    }
    // A period too short for the grains.
    {
        const std::string msg = initializeError({0.05f, 0.2f, 0.2f}, "x", 0.01f, [](DEMSolver&, auto) {});
        EXPECT_NE(msg.find("six times the largest sphere radius"), std::string::npos) << msg;
    }
    // After Initialize.
    sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.1f);
    sim.AddClumps(type, {make_float3(0, 0, 0)});
    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    EXPECT_NE(demeErrorMessage([&] { sim.InstructBoxDomainPeriodicity("x"); }).find("before Initialize"),
              std::string::npos);
}

// Three spheres and a two-sphere clump, each moving along one axis of a fully periodic box with no
// gravity and no contacts, cross the faces (the clump straddles one for a while). Step by step: at the
// step where a centre wraps (jumps by a period) its speed and spin are those of the step before, to
// 1e-6 (relative), and it moved by v dt less one period (to 2e-8 m: trackers report positions as
// floats, whose spacing near 0.1 m is 7.5e-9 m); in the end each centre is where x0 + v t puts it,
// less whole periods (to 1e-7 m).
DEME_BACKEND_TEST(Periodic, GrainsCrossingEachFaceKeepTheirMotion) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    sim.InstructBoxDomainDimension({0.f, 0.1f}, {0.f, 0.1f}, {0.f, 0.1f});
    sim.InstructBoxDomainPeriodicity("xyz");
    const double L = (double)0.1f, dt = 1e-4;
    auto type = sim.LoadSphereType((float)sphereMass(0.005, 2500), 0.005f, mat);
    const std::vector<float3> x0 = {make_float3(0.05f, 0.02f, 0.02f), make_float3(0.02f, 0.05f, 0.08f),
                                    make_float3(0.08f, 0.08f, 0.05f)};
    const std::vector<float3> v = {make_float3(2.f, 0, 0), make_float3(0, -2.f, 0), make_float3(0, 0, 2.5f)};
    auto spheres = sim.AddClumps(type, x0);
    auto dumbbell = sim.LoadClumpType(2e-3f, make_float3(2e-7f, 4e-7f, 4e-7f), {0.004f, 0.004f},
                                      {make_float3(-0.006f, 0, 0), make_float3(0.006f, 0, 0)}, mat);
    auto clump = sim.AddClumps(dumbbell, {make_float3(0.05f, 0.05f, 0.05f)});
    sim.SetInitTimeStep(dt);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.Initialize();
    auto tr = sim.Track(spheres);
    auto ct = sim.Track(clump);
    const float3 w = make_float3(10.f, -20.f, 30.f);
    for (size_t k = 0; k < 3; k++) {
        tr->SetVel(v[k], k);
        tr->SetAngVel(w, k);
    }
    ct->SetVel(make_float3(1.5f, 0, 0));
    // The offset between two positions, less whole periods.
    auto offset = [&](double d) { return d - L * std::round(d / L); };
    std::vector<float3> pBefore(3), vBefore(3), wBefore(3);
    std::vector<int> wraps(3, 0);
    for (int step = 0; step < 750; step++) {  // 0.075 s: the z-mover crosses twice, the others once
        for (size_t k = 0; k < 3; k++) {
            pBefore[k] = tr->Pos(k);
            vBefore[k] = tr->Vel(k);
            wBefore[k] = tr->AngVelGlobal(k);
        }
        sim.DoStepDynamics();
        for (size_t k = 0; k < 3; k++) {
            const float3 p = tr->Pos(k), d = p - pBefore[k];
            if (std::fabs(d.x) + std::fabs(d.y) + std::fabs(d.z) < 0.5 * L) continue;
            wraps[k]++;
            EXPECT_NEAR(offset(d.x), v[k].x * dt, 2e-8) << k;
            EXPECT_NEAR(offset(d.y), v[k].y * dt, 2e-8) << k;
            EXPECT_NEAR(offset(d.z), v[k].z * dt, 2e-8) << k;
            EXPECT_NEAR(length(tr->Vel(k) - vBefore[k]), 0.0, 1e-6 * length(v[k])) << k;
            EXPECT_NEAR(length(tr->AngVelGlobal(k) - wBefore[k]), 0.0, 1e-6 * length(w)) << k;
            // Inside the box after the wrap.
            EXPECT_GE(std::min({p.x, p.y, p.z}), 0.f);
            EXPECT_LE(std::max({p.x, p.y, p.z}), (float)L);
        }
    }
    EXPECT_EQ(wraps, std::vector<int>({1, 1, 2}));
    const double t = sim.GetSimTime();
    for (size_t k = 0; k < 3; k++) {
        const float3 p = tr->Pos(k);
        EXPECT_NEAR(offset(p.x - (x0[k].x + v[k].x * t)), 0.0, 1e-7) << k;
        EXPECT_NEAR(offset(p.y - (x0[k].y + v[k].y * t)), 0.0, 1e-7) << k;
        EXPECT_NEAR(offset(p.z - (x0[k].z + v[k].z * t)), 0.0, 1e-7) << k;
    }
    EXPECT_NEAR(offset(ct->Pos().x - (0.05 + 1.5 * t)), 0.0, 1e-7);
    EXPECT_GT(0.05 + 1.5 * t, L);  // the clump crossed
    EXPECT_NEAR(length(ct->Vel() - make_float3(1.5f, 0, 0)), 0.0, 1e-6);
    EXPECT_EQ(sim.GetNumContacts(), 0u);
}

// Two spheres touching across the x face, and the same pair (the same offset, speeds and spins)
// inside the box: after the first step their contact forces, velocities and spins are the same, bit
// for bit on the CPU (the box's edge, 1 - 2^-21 m, makes every position and image shift exact).
DEME_BACKEND_TEST(Periodic, PairAcrossAFaceFeelsWhatThePairInsideFeels) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.6, 0.4, 0.05));
    const float L = 1.f - std::ldexp(1.f, -21);
    sim.InstructBoxDomainDimension({0.f, L}, {0.f, L}, {0.f, L});
    sim.InstructBoxDomainPeriodicity("x");
    auto type = sim.LoadSphereType((float)sphereMass(0.008, 2500), 0.008f, mat);
    const float h = std::ldexp(1.f, -7);  // half the centre distance, 0.0078125 m (overlap 0.375 mm)
    // Inside: A left of B. Across: A near the upper face, B near the lower one, so that B's nearest
    // image is at the same offset from A.
    auto pairs = sim.AddClumps(type, {make_float3(0.5f - h, 0.25f, 0.25f), make_float3(0.5f + h, 0.25f, 0.25f),
                                      make_float3(L - h, 0.75f, 0.75f), make_float3(h, 0.75f, 0.75f)});
    sim.SetInitTimeStep(1e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.Initialize();
    auto tr = sim.Track(pairs);
    for (size_t k : {0u, 2u}) {
        tr->SetVel(make_float3(0.25f, 0.5f, -0.125f), k);
        tr->SetAngVel(make_float3(4.f, -8.f, 2.f), k);
    }
    for (size_t k : {1u, 3u}) {
        tr->SetVel(make_float3(-0.25f, 0.f, 0.0625f), k);
        tr->SetAngVel(make_float3(-2.f, 1.f, 16.f), k);
    }
    sim.DoStepDynamics();
    EXPECT_EQ(sim.GetNumContacts(), 2u);
    for (size_t k : {0u, 1u}) {
        const float3 fIn = tr->ContactForce(k), fAcross = tr->ContactForce(k + 2);
        EXPECT_GT(length(fIn), 1.f) << k;
        if (!onGpu()) {
            EXPECT_TRUE(same(fIn, fAcross)) << k;
            EXPECT_TRUE(same(tr->Vel(k), tr->Vel(k + 2))) << k;
            EXPECT_TRUE(same(tr->AngVelGlobal(k), tr->AngVelGlobal(k + 2))) << k;
        } else {
            EXPECT_NEAR(length(fIn - fAcross), 0.0, 1e-6 * length(fIn)) << k;
            EXPECT_NEAR(length(tr->Vel(k) - tr->Vel(k + 2)), 0.0, 1e-6) << k;
        }
    }
    // Equal and opposite across the face as inside.
    EXPECT_NEAR(length(tr->ContactForce(2) + tr->ContactForce(3)), 0.0, 1e-6 * length(tr->ContactForce(2)));
}

// An elastic, frictionless gas in a fully periodic box (no walls, no gravity): 300 spheres at about
// 1 m/s, some 250 collisions in 10^4 steps, many of them across faces. Hertz contacts with CoR = 1
// store energy only while they last (about 1 % of the time here), so the kinetic energy comes back
// to within 1 % of its start; the momentum, with nothing outside to push on, to rounding (1e-5 of
// the sum of the grains' momenta).
DEME_BACKEND_TEST(Periodic, ElasticGasKeepsItsEnergyAndMomentum) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e8, 0.3, 1.0, 0.0));
    sim.InstructBoxDomainDimension({0.f, 0.1f}, {0.f, 0.1f}, {0.f, 0.1f});
    sim.InstructBoxDomainPeriodicity("xyz");
    const double r = 0.003;
    auto type = sim.LoadSphereType((float)sphereMass(r, 2500), (float)r, mat);
    std::vector<float3> pts;
    for (int i = 0; i < 7 && pts.size() < 300; i++)
        for (int j = 0; j < 7 && pts.size() < 300; j++)
            for (int k = 0; k < 7 && pts.size() < 300; k++)
                pts.push_back(make_float3(0.007f + 0.0142f * i, 0.007f + 0.0142f * j, 0.007f + 0.0142f * k));
    auto gas = sim.AddClumps(type, pts);
    sim.SetInitTimeStep(5e-6);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.Initialize();
    auto tr = sim.Track(gas);
    std::mt19937 rng(11);
    std::normal_distribution<float> g(0.f, 0.6f);
    std::vector<float3> v0(pts.size());
    for (size_t k = 0; k < pts.size(); k++) {
        v0[k] = make_float3(g(rng), g(rng), g(rng));
        tr->SetVel(v0[k], k);
    }
    auto energy = sim.CreateInspector("clump_kinetic_energy");
    auto momentum = [&] {
        double3 p = make_double3(0, 0, 0);
        double scale = 0.0;
        for (size_t k = 0; k < pts.size(); k++) {
            const float3 v = tr->Vel(k);
            p = p + to_double3(v);
            scale += length(v);
        }
        return std::make_pair(p, scale);
    };
    const double e0 = energy->GetValue();
    const auto [p0, s0] = momentum();
    size_t collisions = 0;
    for (int frame = 0; frame < 100; frame++) {
        sim.DoDynamics(100 * 5e-6);
        collisions += sim.GetNumContacts();
    }
    const auto [p1, s1] = momentum();
    EXPECT_GT(collisions, 30u);  // contacts seen at 100 instants, each lasting ~60 steps
    EXPECT_NEAR(energy->GetValue(), e0, 0.01 * e0);
    EXPECT_NEAR(length(p1 - p0), 0.0, 1e-5 * s0);
}
