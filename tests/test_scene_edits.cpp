// Scenes that change while they run (docs/scene-changes.md): clumps added with AddClumps +
// UpdateClumps between DoDynamics calls, clumps removed by family or when they leave the domain
// (SetDomainExitPolicy("remove")), on every backend.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "BackendFixture.h"
#include "HopperGeometry.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(SceneEdits);

namespace {

double distance(const float3& a, const float3& b) {
    const double dx = (double)a.x - b.x, dy = (double)a.y - b.y, dz = (double)a.z - b.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

}  // namespace

// A dumbbell clump (two spheres r = 0.05 m, 1 kg) rests on a plane tilted by 15 degrees (gravity
// tilted, as in the incline test), held by static friction (tan 15 = 0.27 < mu = 0.5): the tangential
// springs of its two contacts carry m g sin 15 = 2.5 N. Were their history lost at an insertion, the
// springs would restart from zero and the clump would creep until they carry the load again:
// delta_t = F_t / k_t with k_t = 8 G* sqrt(R delta_n) (Mindlin) ~ 3.5e4 N/m per contact, i.e.
// ~4e-5 m, forty times the 1e-6 m it may move here. Grains are inserted (and later removed) far down
// the slope, which renumbers the plane's geometry id in the contact set each time.
DEME_BACKEND_TEST(SceneEdits, InsertionKeepsTheHistoryOfAClumpStuckOnASlope) {
    const double r = 0.05, m = 1.0, g = 9.81, alpha = 15.0 * deme::PI / 180.0;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.5));
    sim.InstructBoxDomainDimension({-2.f, 2.f}, {-1.f, 1.f}, {-0.5f, 1.5f});
    auto plane = sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    const float I1 = (float)(2 * 0.4 * 0.5 * r * r), I2 = (float)(I1 + 2 * 0.5 * r * r);
    auto dumbbell = sim.LoadClumpType((float)m, make_float3(I1, I2, I2), {(float)r, (float)r},
                                      {make_float3((float)-r, 0, 0), make_float3((float)r, 0, 0)}, mat);
    // Static Hertz overlap of each sphere under half the normal load.
    const double Estar = effectiveModulus(1e7, 0.3);
    const double overlap = std::pow(0.5 * m * g * std::cos(alpha) / (4.0 / 3.0 * Estar * std::sqrt(r)), 2.0 / 3.0);
    auto resting = sim.AddClumps(dumbbell, {make_float3(1.5f, 0, (float)(r - overlap))});
    sim.SetInitTimeStep(1e-4);
    sim.SetGravitationalAcceleration(make_float3((float)(-g * std::sin(alpha)), 0, (float)(-g * std::cos(alpha))));
    sim.Initialize();
    auto tr = sim.Track(resting);
    sim.DoDynamics(1.0);  // settles (CoR 0.3 damps the first oscillations within a few tens of ms)
    const float3 p0 = tr->Pos();
    ASSERT_LT(length(tr->Vel()), 1e-4f);

    auto ball = sim.LoadSphereType((float)sphereMass(0.03, 2500), 0.03f, mat);
    std::vector<std::shared_ptr<DEMTracker>> added;
    for (int round = 0; round < 4; round++) {
        std::vector<float3> pos;
        for (int i = 0; i < 5; i++) pos.push_back(make_float3(-1.0f + 0.1f * i, 0.1f * round - 0.2f, 0.3f));
        auto batch = sim.AddClumps(ball, pos);
        batch->SetFamily(round == 1 ? 7 : 5);
        EXPECT_EQ(batch->GetOwnerOffset(), 2u + 5u * round) << "new ids follow the dumbbell (0) and the plane (1)";
        auto t = sim.Track(batch);
        sim.UpdateClumps();
        EXPECT_EQ(sim.GetNumClumps(), 1u + 5u * (round + 1) - (round >= 3 ? 5u : 0u));
        EXPECT_LT(distance(t->Pos(4), pos[4]), 1e-6);
        EXPECT_EQ(t->GetOwnerID(0), 2u + 5u * round);
        added.push_back(t);
        if (round == 2) EXPECT_EQ(sim.RemoveClumpsInFamily(7), 5u);  // the second batch goes
        sim.DoDynamics(0.1);
        EXPECT_LT(distance(tr->Pos(), p0), 1e-6) << "round " << round;
        EXPECT_EQ(tr->GetOwnerID(), 0u);
    }
    // The grains fell onto the plane and stayed on it (the tracker of the first batch still reads it).
    EXPECT_NEAR(added[0]->Pos(0).z, 0.03, 2e-3);
    // The removed batch's tracker says so; the plane is still owner 1.
    EXPECT_NE(demeErrorMessage([&] { added[1]->Pos(0); }).find("was removed"), std::string::npos);
    EXPECT_EQ(sim.Track(plane)->GetOwnerID(), 1u);
    EXPECT_EQ(sim.GetNumRemovedClumps(), 5u);
    EXPECT_DOUBLE_EQ(sim.GetRemovedMass(), 5.0 * (double)(float)sphereMass(0.03, 2500));
}

namespace {

// Spheres (r = 1 cm) in a 10 cm square box with frictionless side walls: at rest, the floor carries
// the whole weight N m g (the side walls push only sideways). Layer k of 8 spheres starts at
// z = 3 cm + 2.5 cm k; `layers` pours put them in one by one, each after the previous has settled.
double settledFloorForce(int pours, double& weight) {
    const float r = 0.01f;
    const double m = sphereMass(r, 2500), g = 9.81;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto grainMat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.3));
    auto wallMat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.0));
    sim.SetMaterialPropertyPair("mu", grainMat, wallMat, 0.0);
    sim.InstructBoxDomainDimension({-0.05f, 0.05f}, {-0.05f, 0.05f}, {0.f, 0.4f});
    auto floor = sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), grainMat);
    sim.AddBCPlane(make_float3(-0.05f, 0, 0), make_float3(1, 0, 0), wallMat);
    sim.AddBCPlane(make_float3(0.05f, 0, 0), make_float3(-1, 0, 0), wallMat);
    sim.AddBCPlane(make_float3(0, -0.05f, 0), make_float3(0, 1, 0), wallMat);
    sim.AddBCPlane(make_float3(0, 0.05f, 0), make_float3(0, -1, 0), wallMat);
    auto grain = sim.LoadSphereType((float)m, r, grainMat);
    auto layer = [&](int k) {
        std::vector<float3> p;
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 4; i++)
                p.push_back(make_float3(-0.03f + 0.02f * i + 0.002f * k, -0.015f + 0.03f * j, 0.03f + 0.025f * k));
        return p;
    };
    const int nLayers = 5;
    if (pours == 1)
        for (int k = 0; k < nLayers; k++) sim.AddClumps(grain, layer(k));
    else
        sim.AddClumps(grain, layer(0));
    sim.SetInitTimeStep(2e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-g));
    sim.Initialize();
    auto tr = sim.Track(floor);
    for (int k = 1; k < nLayers && pours > 1; k++) {
        sim.DoDynamics(0.3);
        sim.AddClumps(grain, layer(k));
        sim.UpdateClumps();
    }
    sim.DoDynamics(0.8);
    auto vmax = sim.CreateInspector("clump_max_absv");
    EXPECT_LT(vmax->GetValue(), 5e-3) << pours << " pours: not settled";
    EXPECT_EQ(sim.GetNumClumps(), 8u * nLayers);
    weight = 8.0 * nLayers * (double)(float)m * g;
    return (double)tr->ContactForce().z;
}

}  // namespace

// Newton: a bed at rest on a floor with frictionless side walls loads the floor with its weight.
// Poured in five layers or in one, the settled bed must give the same floor force (within 1 %).
DEME_BACKEND_TEST(SceneEdits, FiveLayerPourSettlesToTheSameFloorForceAsOnePour) {
    double weight = 0.0;
    const double one = settledFloorForce(1, weight);
    const double five = settledFloorForce(5, weight);
    EXPECT_NEAR(-one, weight, 0.01 * weight) << "one pour";  // the force on the floor points down
    EXPECT_NEAR(five, one, 0.01 * std::fabs(one));
}

// A hopper (demos/HopperGeometry.h) empties through its orifice; grains leaving through the domain's
// floor are removed. Nothing is lost: removed mass + mass left == initial mass, exactly (each mass is
// a float, and sums of a few hundred floats are exact in double precision, whatever their order).
// With asynchronous detection, each removal also drops the kinematics thread's order in flight.
void dischargeHopper(bool async) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    HopperSpec spec;
    const Hopper h = buildHopper(sim, spec);
    sim.SetInitTimeStep(2e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetDomainExitPolicy("remove");
    sim.SetSynchronousContactDetection(!async);
    sim.Initialize();
    ASSERT_EQ(sim.UsesAsyncContactDetection(), async);
    auto mass = sim.CreateInspector("clump_mass");
    auto lowest = sim.CreateInspector("clump_min_z");
    const double initial = mass->GetValue();
    const size_t n = sim.GetNumClumps();
    auto tr = sim.Track(h.grains);
    size_t last = 0;
    for (int frame = 0; frame < 10; frame++) {
        sim.DoDynamics(0.1);
        EXPECT_GE(sim.GetNumRemovedClumps(), last);
        last = sim.GetNumRemovedClumps();
        EXPECT_EQ(sim.GetNumClumps() + last, n);
        EXPECT_EQ(sim.GetRemovedMass() + mass->GetValue(), initial) << "frame " << frame;
        if (sim.GetNumClumps()) EXPECT_GE(lowest->GetValue(), spec.domainBottom);
    }
    EXPECT_GE(last, n / 4) << "the orifice (4.4 grain diameters) lets a good part of the grains out";
    EXPECT_LT(last, n) << "a flat-bottomed hopper keeps its dead zones";
    // Rows of grains still in the hopper keep their ids; the removed ones' rows say they are gone.
    size_t alive = 0;
    for (size_t i = 0; i < n; i++) {
        try {
            EXPECT_GT(tr->Pos(i).z, spec.domainBottom);
            EXPECT_EQ(tr->GetOwnerID(i), i);
            alive++;
        } catch (const deme::Error& e) {
            EXPECT_NE(std::string(e.what()).find("was removed"), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(alive, sim.GetNumClumps());
    EXPECT_DOUBLE_EQ(sim.GetRemovedMass(), (double)last * (double)(float)h.grainMass);
}

DEME_BACKEND_TEST(SceneEdits, HopperDischargeRemovesLeavingGrainsAndConservesMass) { dischargeHopper(false); }

DEME_BACKEND_TEST(SceneEdits, HopperDischargeWithAsynchronousDetection) { dischargeHopper(true); }

// The default policy stops the run at the first grain that leaves, naming it.
DEME_BACKEND_TEST(SceneEdits, DefaultExitPolicyStopsTheRunNamingTheGrain) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    buildHopper(sim, HopperSpec{});
    sim.SetInitTimeStep(2e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.Initialize();
    const std::string msg = demeErrorMessage([&] { sim.DoDynamics(1.0); });
    EXPECT_NE(msg.find("DoDynamics"), std::string::npos) << msg;
    EXPECT_NE(msg.find("left the simulation domain"), std::string::npos) << msg;
    EXPECT_EQ(sim.GetNumRemovedClumps(), 0u);
}

// Every owner of the scene falls out of the domain under the "remove" policy: the run goes on with
// none left (every per-owner sweep over nothing), and the removed mass is all the mass there was.
DEME_BACKEND_TEST(SceneEdits, RunGoesOnWhenEveryGrainHasLeft) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.5));
    sim.InstructBoxDomainDimension(1, 1, 1);
    const double r = 0.01, m = sphereMass(r, 1000);
    auto ball = sim.LoadSphereType((float)m, (float)r, mat);
    sim.AddClumps(ball, {make_float3(0, 0, -0.3f), make_float3(0.2f, 0, -0.2f)});
    sim.SetDomainExitPolicy("remove");
    sim.SetInitTimeStep(1e-4);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.Initialize();
    sim.DoDynamics(0.4);  // both fall out through z = -0.5 within 0.32 s
    EXPECT_EQ(sim.GetNumClumps(), 0u);
    EXPECT_EQ(sim.GetNumRemovedClumps(), 2u);
    EXPECT_NEAR(sim.GetRemovedMass(), 2 * m, 1e-6 * m);
    sim.DoDynamics(0.01);  // and further steps with nothing to step
    EXPECT_NEAR(sim.GetSimTime(), 0.41, 1e-9);
}

// A column of 60 spheres falls from rest out through the domain's floor (no wall), one after the
// other, in one DoDynamics call. A clump that leaves is parked by its step and removed at the call's
// end (dynamics/OwnerStep.h, parkingPosition), so the exits end no batches: the call ends as many
// batches early (sets that expire as the column speeds up) as the same fall in a domain reaching
// 1 m lower, which nobody leaves. Before parking, each exit ended its batch for a host round trip
// (60 more). Synchronous detection, so that batches end only by the step rule. Between calls the
// removed count is the free fall's: sphere i (z_i = 2 + 4 i mm) leaves at sqrt(2 z_i / g), none
// within 1 % of a call's end (0.05, 0.08, 0.11 s; the integrator's lag is some 0.005 %).
DEME_BACKEND_TEST(SceneEdits, ClumpsLeavingInACallAreRemovedAtItsEndWithoutEndingBatches) {
    constexpr int N = 60;
    constexpr double g = 9.81, r = 0.001;
    auto column = [&](DEMSolver& sim, float bottom) {
        sim.SetVerbosity("QUIET");
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.3));
        sim.InstructBoxDomainDimension({-0.01f, 0.01f}, {-0.01f, 0.01f}, {bottom, 0.3f});
        auto ball = sim.LoadSphereType((float)sphereMass(r, 2500), (float)r, mat);
        std::vector<float3> at;
        for (int i = 0; i < N; i++) at.push_back(make_float3(0, 0, 0.002f + 0.004f * (float)i));
        sim.AddClumps(ball, at);
        sim.SetDomainExitPolicy("remove");
        sim.SetSynchronousContactDetection(true);
        sim.SetInitTimeStep(1e-5);
        sim.SetGravitationalAcceleration(make_float3(0, 0, -(float)g));
        sim.Initialize();
    };
    auto leftBy = [&](double t) {
        int n = 0;
        for (int i = 0; i < N; i++) n += std::sqrt(2.0 * (0.002 + 0.004 * i) / g) < t ? 1 : 0;
        return (size_t)n;
    };
    DEMSolver one, kept;
    column(one, 0.f);
    column(kept, -1.f);
    one.DoDynamics(0.25);   // the last leaves at 0.22 s
    kept.DoDynamics(0.25);  // the lowest has fallen 0.31 m
    EXPECT_EQ(one.GetNumRemovedClumps(), (size_t)N);
    EXPECT_EQ(one.GetNumClumps(), 0u);
    EXPECT_EQ(kept.GetNumRemovedClumps(), 0u);
    EXPECT_LE(batchesEndedEarly(one), batchesEndedEarly(kept) + 5u) << "exits ended batches";

    DEMSolver frames;
    column(frames, 0.f);
    double now = 0.0;
    for (double t : {0.05, 0.08, 0.11, 0.25}) {
        frames.DoDynamics(t - now);
        now = t;
        EXPECT_EQ(frames.GetNumRemovedClumps(), leftBy(t)) << "t = " << t;
        EXPECT_EQ(frames.GetNumClumps() + frames.GetNumRemovedClumps(), (size_t)N);
    }
}

// A parked clump touches nothing: a ball resting on a floor (an analytical plane, z = 0) and a ball
// thrown out of the domain sideways, in one call. The thrown one waits parked (far beyond the domain
// along x, at the domain's lowest z: 0.1 m below the floor's plane) from its exit at about 0.02 s to
// the call's end, where it is removed. The floor carries the resting ball's weight in the call's
// last step (to 1 %: it has come to rest in the 0.3 s before), not the parked one's overlap with the
// infinite plane (0.11 m: 26,727 N at E = 10^7 Pa), which a parked sphere once exerted on it.
DEME_BACKEND_TEST(SceneEdits, ParkedClumpExertsNothingOnAnInfinitePlane) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.5));
    sim.InstructBoxDomainDimension({-0.5f, 0.5f}, {-0.5f, 0.5f}, {-0.1f, 0.4f});
    auto floor = sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    const double r = 0.01, m = sphereMass(r, 1000), g = 9.81;
    auto ball = sim.LoadSphereType((float)m, (float)r, mat);
    sim.AddClumps(ball, {make_float3(0, 0, (float)r)});  // the resting ball
    auto thrown = sim.AddClumps(ball, {make_float3(0.3f, 0, 0.3f)});
    sim.SetDomainExitPolicy("remove");
    sim.SetInitTimeStep(1e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -(float)g));
    sim.Initialize();
    auto tf = sim.Track(floor), tt = sim.Track(thrown);
    sim.DoDynamics(0.3);  // the resting ball settles; the other falls from 0.3 m, 0.25 s to the floor
    EXPECT_EQ(sim.GetNumRemovedClumps(), 0u);
    tt->SetPos(make_float3(0.3f, 0, 0.3f));
    tt->SetVel(make_float3(10.f, 0, 0));  // out through x = 0.5 after 0.02 s
    sim.DoDynamics(0.05);
    EXPECT_EQ(sim.GetNumRemovedClumps(), 1u);
    EXPECT_NEAR(tf->ContactForce().z, -m * g, 0.01 * m * g);
    sim.DoDynamics(0.01);  // and after the removal
    EXPECT_NEAR(tf->ContactForce().z, -m * g, 0.01 * m * g);
}

// Bad input: each a deme::Error naming the call, with nothing changed.
DEME_BACKEND_TEST(SceneEdits, BadInputIsAnErrorNamingTheCall) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.3));
    sim.InstructBoxDomainDimension(1, 1, 1);
    auto grain = sim.LoadSphereType(1.f, 0.05f, mat);
    sim.AddClumps(grain, {make_float3(0, 0, 0)});
    EXPECT_NE(demeErrorMessage([&] { sim.UpdateClumps(); }).find("UpdateClumps"), std::string::npos);
    EXPECT_NE(demeErrorMessage([&] { sim.RemoveClumpsInFamily(1); }).find("RemoveClumpsInFamily"), std::string::npos);
    const std::string policy = demeErrorMessage([&] { sim.SetDomainExitPolicy("delete"); });
    EXPECT_NE(policy.find("SetDomainExitPolicy"), std::string::npos) << policy;
    EXPECT_NE(policy.find("delete"), std::string::npos) << policy;
    sim.SetInitTimeStep(1e-4);
    sim.Initialize();

    const std::string outside = demeErrorMessage([&] { sim.AddClumps(grain, {make_float3(0, 0, 0.2f), make_float3(0, 0, 0.7f)}); });
    EXPECT_NE(outside.find("AddClumps"), std::string::npos) << outside;
    EXPECT_NE(outside.find("outside the simulation domain"), std::string::npos) << outside;
    const std::string family = demeErrorMessage([&] { sim.RemoveClumpsInFamily(256); });
    EXPECT_NE(family.find("RemoveClumpsInFamily"), std::string::npos) << family;
    EXPECT_EQ(sim.RemoveClumpsInFamily(9), 0u) << "a family without clumps removes none";

    // A batch waiting for UpdateClumps: DoDynamics refuses to run, its tracker is not live yet.
    auto waiting = sim.AddClumps(grain, {make_float3(0.2f, 0, 0)});
    auto tw = sim.Track(waiting);
    EXPECT_NE(demeErrorMessage([&] { sim.DoDynamics(0.01); }).find("UpdateClumps"), std::string::npos);
    EXPECT_NE(demeErrorMessage([&] { sim.DoStepDynamics(); }).find("UpdateClumps"), std::string::npos);
    EXPECT_NE(demeErrorMessage([&] { tw->Pos(); }).find("UpdateClumps"), std::string::npos);
    EXPECT_EQ(sim.GetNumClumps(), 1u);
    sim.UpdateClumps();
    EXPECT_EQ(sim.GetNumClumps(), 2u);
    EXPECT_EQ(tw->GetOwnerID(), 1u);
    EXPECT_LT(distance(tw->Pos(), make_float3(0.2f, 0, 0)), 1e-6);
    sim.DoDynamics(0.01);
}
