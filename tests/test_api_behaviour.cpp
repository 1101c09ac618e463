// API behaviour that the physics tests do not cover: trackers, inspectors, contact masks,
// family changes, moving analytical objects, on every backend; and template scaling (no simulation).
#include <gtest/gtest.h>

#include <cmath>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(Api);

namespace {

struct TwoBalls {
    DEMSolver sim;
    std::shared_ptr<DEMMaterial> mat;
    std::shared_ptr<DEMClumpBatch> a, b;
    explicit TwoBalls(float vA = 1.f) {
        sim.SetVerbosity("QUIET");
        mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.3));
        sim.InstructBoxDomainDimension(2, 2, 2);
        auto t = sim.LoadSphereType(1.f, 0.05f, mat);
        a = sim.AddClumps(t, {make_float3(-0.2f, 0, 0)});
        b = sim.AddClumps(t, {make_float3(0.2f, 0, 0)});
        a->SetVel(make_float3(vA, 0, 0));
        sim.SetInitTimeStep(1e-4);
    }
};

}  // namespace

DEME_BACKEND_TEST(Api, DisabledFamiliesPassThroughEachOther) {
    TwoBalls s;
    s.b->SetFamily(5);
    s.sim.DisableContactBetweenFamilies(0, 5);
    s.sim.Initialize();
    auto ta = s.sim.Track(s.a);
    s.sim.DoDynamics(0.5);  // A travels 0.5 m through B
    EXPECT_NEAR(ta->Pos().x, 0.3, 1e-4);
    EXPECT_FLOAT_EQ(ta->Vel().x, 1.f);
    // Re-enabled, the next meeting is a collision: A moving back to the left hits B from the right.
    s.sim.EnableContactBetweenFamilies(0, 5);
    ta->SetPos(make_float3(0.4f, 0, 0));
    ta->SetVel(make_float3(-1.f, 0, 0));
    s.sim.DoDynamics(0.5);
    EXPECT_GT(ta->Vel().x, -0.9f);  // slowed or reversed by the collision
}

DEME_BACKEND_TEST(Api, ChangeFamilyReleasesAFixedClump) {
    TwoBalls s(0.f);
    s.a->SetFamily(1);
    s.sim.SetFamilyFixed(1);
    s.sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    s.sim.Initialize();
    auto ta = s.sim.Track(s.a);
    const float z0 = ta->Pos().z;  // 0 to within the position resolution
    s.sim.DoDynamics(0.1);
    EXPECT_EQ(ta->Pos().z, z0);
    s.sim.ChangeFamily(1, 2);
    EXPECT_EQ(ta->GetFamily(), 2u);
    s.sim.DoDynamics(0.1);
    EXPECT_NEAR(ta->Pos().z, -0.5 * 9.81 * 0.1 * 0.1, 1e-3);  // free fall, first-order integration
}

DEME_BACKEND_TEST(Api, TrackerSettersAndLoads) {
    TwoBalls s(0.f);
    s.sim.Initialize();
    auto ta = s.sim.Track(s.a);
    EXPECT_EQ(ta->GetOwnerID(), 0u);
    EXPECT_FLOAT_EQ(ta->Mass(), 1.f);
    EXPECT_NEAR(ta->MOI().x, 0.4 * 1.0 * 0.05 * 0.05, 1e-9);
    ta->SetPos(make_float3(-0.5f, 0.1f, 0.2f));
    EXPECT_NEAR(ta->Pos().y, 0.1, 1e-6);
    // AddAcc acts during the next call only: v = a t, then constant.
    ta->AddAcc(make_float3(0, 2.f, 0));
    s.sim.DoDynamics(0.1);
    EXPECT_NEAR(ta->Vel().y, 0.2, 1e-5);
    s.sim.DoDynamics(0.1);
    EXPECT_NEAR(ta->Vel().y, 0.2, 1e-5);
    // A quarter turn about z set through the orientation.
    const float h = std::sqrt(0.5f);
    ta->SetOriQ(make_float4(0, 0, h, h));
    EXPECT_NEAR(ta->OriQ().z, h, 1e-6);
    ta->SetAngVel(make_float3(0, 0, 3.f));
    EXPECT_NEAR(ta->AngVelGlobal().z, 3.f, 1e-6);
}

DEME_BACKEND_TEST(Api, InspectorsReduceOverClumps) {
    TwoBalls s(2.f);
    s.sim.Initialize();
    auto tb = s.sim.Track(s.b);
    tb->SetPos(make_float3(0.2f, 0.f, 0.3f));
    EXPECT_NEAR(s.sim.CreateInspector("clump_max_z")->GetValue(), 0.3, 1e-6);
    EXPECT_NEAR(s.sim.CreateInspector("clump_min_z")->GetValue(), 0.0, 1e-6);
    EXPECT_NEAR(s.sim.CreateInspector("clump_max_absv")->GetValue(), 2.0, 1e-6);
    EXPECT_NEAR(s.sim.CreateInspector("clump_kinetic_energy")->GetValue(), 0.5 * 1.0 * 4.0, 1e-6);
}

// An external object with a prescribed velocity: a plane rising at 0.1 m/s lifts a resting ball,
// which then moves with it; the tracker reports the load the ball puts on the plane.
DEME_BACKEND_TEST(Api, PrescribedAnalyticalObjectCarriesABall) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.2, 0.3));
    sim.InstructBoxDomainDimension(2, 2, 2);
    auto lift = sim.AddExternalObject();
    lift->AddPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    lift->SetInitPos(make_float3(0, 0, -0.5f));
    lift->SetFamily(7);
    sim.SetFamilyPrescribedLinVel(7, "0", "0", "0.1");
    auto ball = sim.AddClumps(sim.LoadSphereType(1.f, 0.05f, mat), {make_float3(0, 0, -0.45f)});
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetInitTimeStep(1e-4);
    sim.Initialize();
    auto tl = sim.Track(lift), tb = sim.Track(ball);
    sim.DoDynamics(1.0);
    EXPECT_NEAR(tl->Pos().z, -0.4, 1e-4);
    EXPECT_NEAR(tb->Vel().z, 0.1, 0.01);
    EXPECT_NEAR(tb->Pos().z, -0.35, 0.005);         // rests on the plane, 5 cm up
    EXPECT_NEAR(-tl->ContactForce().z, 9.81, 0.1);  // carries the ball's weight
}

// No simulation starts here: a plain test, apart from the backend suite above.
TEST(ApiTemplate, ScaleScalesMassAndInertia) {
    DEMSolver sim;
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.3));
    auto t = sim.LoadClumpType(2.f, make_float3(1.f, 2.f, 3.f), {0.5f, 0.25f},
                               {make_float3(1.f, 0, 0), make_float3(0, -1.f, 0)}, mat);
    t->Scale(2.f);
    EXPECT_FLOAT_EQ(t->mass, 16.f);
    EXPECT_FLOAT_EQ(t->MOI.z, 96.f);
    EXPECT_FLOAT_EQ(t->radii[1], 0.5f);
    EXPECT_FLOAT_EQ(t->relPos[0].x, 2.f);
    EXPECT_FLOAT_EQ(t->GetExtent(), 3.f);
}

namespace {
// A quiet CPU solver in a 1 m box, and the material of the batch tests' spheres.
std::shared_ptr<DEMMaterial> batchTestSolver(DEMSolver& sim) {
    sim.SetBackend("cpu");
    sim.SetVerbosity("QUIET");
    sim.InstructBoxDomainDimension(1, 1, 1);
    return sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.3));
}
}  // namespace

// At Initialize the solver takes a batch's clumps into its state and the batch lets go of its
// per-clump arrays (docs/memory.md): its getters of initial values are errors naming the call, its
// count and owner offset stay, and trackers read the clumps. The same for UpdateClumps.
TEST(ApiBatch, InitializeTakesTheBatchsArrays) {
    DEMSolver sim;
    auto mat = batchTestSolver(sim);
    auto t = sim.LoadSphereType(1.f, 0.01f, mat);
    auto a = sim.AddClumps(t, {make_float3(0, 0, 0), make_float3(0.1f, 0, 0)});
    EXPECT_EQ(a->GetPositions().size(), 2u);
    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    EXPECT_EQ(a->GetNumClumps(), 2u);
    EXPECT_NE(demeErrorMessage([&] { a->GetPositions(); }).find("DEMClumpBatch::GetPositions: the batch's clumps are in "
                                                                "the solver's state"),
              std::string::npos);
    EXPECT_NE(demeErrorMessage([&] { a->GetFamilies(); }).find("DEMClumpBatch::GetFamilies"), std::string::npos);
    EXPECT_NE(demeErrorMessage([&] { a->SetVel(make_float3(1, 0, 0)); }).find("already initialized"), std::string::npos);
    EXPECT_NEAR(sim.Track(a)->Pos(1).x, 0.1, 1e-6);

    auto b = sim.AddClumps(t, {make_float3(0.3f, 0, 0)});
    EXPECT_EQ(b->GetPositions().size(), 1u);  // waiting for UpdateClumps: still the batch's own
    sim.UpdateClumps();
    EXPECT_EQ(b->GetNumClumps(), 1u);
    EXPECT_NE(demeErrorMessage([&] { b->GetOriQs(); }).find("DEMClumpBatch::GetOriQs"), std::string::npos);
    EXPECT_NEAR(sim.Track(b)->Pos().x, 0.3, 1e-6);
}

// A batch keeps each template once and an index per clump only where its clumps differ
// (docs/memory.md): GetTypes() rebuilds the per-clump list as given, GetType(i) reads one, and both
// survive Initialize (the templates stay with the batch); an index past the batch is an error.
TEST(ApiBatch, TemplatesOnceEachWithAnIndexPerClump) {
    DEMSolver sim;
    auto mat = batchTestSolver(sim);
    auto small = sim.LoadSphereType(1.f, 0.01f, mat);
    auto large = sim.LoadSphereType(2.f, 0.02f, mat);
    auto mixed = sim.AddClumps({large, small, large, small, small},
                               {make_float3(0, 0, 0), make_float3(0.1f, 0, 0), make_float3(0.2f, 0, 0),
                                make_float3(0.3f, 0, 0), make_float3(-0.1f, 0, 0)});
    auto same = sim.AddClumps(small, {make_float3(0, 0.2f, 0), make_float3(0, 0.3f, 0)});
    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    const std::vector<std::shared_ptr<DEMClumpTemplate>> given{large, small, large, small, small};
    EXPECT_EQ(mixed->GetTypes(), given);
    EXPECT_EQ(mixed->GetDistinctTypes(), (std::vector<std::shared_ptr<DEMClumpTemplate>>{large, small}));
    for (size_t i = 0; i < given.size(); i++) EXPECT_EQ(mixed->GetType(i), given[i]) << i;
    EXPECT_EQ(same->GetTypes(), (std::vector<std::shared_ptr<DEMClumpTemplate>>{small, small}));
    EXPECT_EQ(same->GetDistinctTypes(), std::vector<std::shared_ptr<DEMClumpTemplate>>{small});
    EXPECT_EQ(same->GetType(1), small);
    EXPECT_NE(demeErrorMessage([&] { same->GetType(2); }).find("DEMClumpBatch::GetType: clump 2 of a batch of 2"),
              std::string::npos);
    // The solver assembled each clump from its own template: masses 2, 1, 2, 1, 1 and 1, 1.
    EXPECT_EQ(sim.GetNumSpheres(), 7u);
    auto tr = sim.Track(mixed);
    EXPECT_FLOAT_EQ(tr->Mass(0), 2.f);
    EXPECT_FLOAT_EQ(tr->Mass(1), 1.f);
    EXPECT_FLOAT_EQ(tr->Mass(4), 1.f);
}

// A value every clump of a batch shares is kept once (the defaults, or a setter given one value):
// 41 of a clump's 53 bytes of initial values are never made for such a batch. A getter makes the
// list; a per-clump setter keeps one value each; the solver's clumps take what was set, either way.
TEST(ApiBatch, SharedInitialValuesAreKeptOnce) {
    DEMSolver sim;
    auto mat = batchTestSolver(sim);
    auto ball = sim.LoadSphereType(1.f, 0.004f, mat);
    const size_t n = 1000;
    std::vector<float3> pos;
    for (size_t i = 0; i < n; i++)
        pos.push_back(make_float3(-0.45f + 0.01f * (float)(i % 90), -0.4f + 0.02f * (float)(i / 90), 0.f));
    auto shared = sim.AddClumps(ball, pos);
    std::vector<float3> above(pos.begin(), pos.begin() + 10);
    for (float3& p : above) p.z = 0.3f;
    auto own = sim.AddClumps(ball, above);
    const size_t positions = n * sizeof(float3), sharedValues = 2 * sizeof(float3) + sizeof(float4) + sizeof(family_t);
    const size_t templates = sizeof(std::shared_ptr<DEMClumpTemplate>);
    EXPECT_EQ(shared->GetHostBytes(), positions + sharedValues + templates);
    shared->SetVel(make_float3(0.1f, 0, 0));
    shared->SetAngVel(make_float3(0, 2.f, 0));
    shared->SetOriQ(make_float4(0, 0, 1, 1));  // normalised: 90 degrees about z
    shared->SetFamily(3);
    EXPECT_EQ(shared->GetHostBytes(), positions + sharedValues + templates) << "one value each still";
    sim.ChangeFamily(3, 4);  // before Initialize: the batch's shared family is renamed in place
    EXPECT_EQ(shared->GetHostBytes(), positions + sharedValues + templates);
    // One value per clump where given so; a list of the wrong length is an error naming the call.
    std::vector<float3> w(10);
    for (size_t i = 0; i < 10; i++) w[i] = make_float3(0, 0, (float)i);
    own->SetAngVel(w);
    EXPECT_NE(demeErrorMessage([&] { own->SetVel(std::vector<float3>(9)); }).find("DEMClumpBatch::SetVel: got 9 values for 10"),
              std::string::npos);
    // A getter makes the list (and the batch then holds it).
    const std::vector<float3>& v = shared->GetVelocities();
    ASSERT_EQ(v.size(), n);
    EXPECT_EQ(v[n - 1].x, 0.1f);
    EXPECT_EQ(shared->GetHostBytes(), positions + sharedValues - sizeof(float3) + n * sizeof(float3) + templates);
    EXPECT_EQ(shared->GetFamilies(), std::vector<family_t>(n, 4));
    ASSERT_EQ(own->GetAngVelocities().size(), 10u);
    EXPECT_EQ(own->GetAngVelocities()[9].z, 9.f);

    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    auto ts = sim.Track(shared), to = sim.Track(own);
    for (size_t i : {size_t(0), n / 2, n - 1}) {
        EXPECT_EQ(ts->Vel(i).x, 0.1f);
        EXPECT_NEAR(ts->AngVelLocal(i).y, 2.f, 1e-6f);
        EXPECT_NEAR(ts->OriQ(i).z, std::sqrt(0.5f), 1e-6f);
        EXPECT_EQ(ts->GetFamily(i), 4u);
    }
    for (size_t i = 0; i < 10; i++) {
        EXPECT_EQ(to->AngVelLocal(i).z, (float)i);
        EXPECT_EQ(to->Vel(i).x, 0.f);
        EXPECT_EQ(to->GetFamily(i), 0u);
    }
}

// A batch's initial values are freed when the solver takes its clumps (not only emptied: an
// assignment of an empty list would keep their storage), and what it keeps is counted in the
// memory table's owner state: nothing per clump for one template, a 4-byte index for several.
TEST(ApiBatch, HandedOverBatchesFreeTheirInitialValues) {
    DEMSolver sim;
    auto mat = batchTestSolver(sim);
    auto small = sim.LoadSphereType(1.f, 0.01f, mat);
    auto large = sim.LoadSphereType(2.f, 0.02f, mat);
    std::vector<float3> pos;
    for (int i = 0; i < 30; i++) pos.push_back(make_float3(-0.4f + 0.025f * i, 0, 0));
    auto same = sim.AddClumps(small, pos);
    for (float3& p : pos) p.y = 0.2f;
    auto mixed = sim.AddClumps(std::vector<std::shared_ptr<DEMClumpTemplate>>(30, small), pos);
    auto two = sim.AddClumps({small, large}, {make_float3(0, -0.2f, 0), make_float3(0.1f, -0.2f, 0)});
    // Positions (12 B each); the velocities, angular velocities, orientations and families every
    // clump shares, once each (41 B; ApiBatch.SharedInitialValuesAreKeptOnce).
    EXPECT_GE(same->GetHostBytes(), 30u * 12 + 41);
    EXPECT_LT(same->GetHostBytes(), 30u * 12 + 41 + 64);
    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    EXPECT_EQ(same->GetHostBytes(), sizeof(std::shared_ptr<DEMClumpTemplate>));
    EXPECT_EQ(mixed->GetHostBytes(), sizeof(std::shared_ptr<DEMClumpTemplate>));  // one template after all
    EXPECT_EQ(two->GetHostBytes(), 2 * sizeof(std::shared_ptr<DEMClumpTemplate>) + 2 * sizeof(uint32_t));
    // A batch added during the run holds its values until UpdateClumps, and the table counts them.
    const size_t before = sim.GetMemoryStats().hostBytes[(int)MemoryGroup::OWNER_STATE];
    auto late = sim.AddClumps(small, {make_float3(0, 0.4f, 0)});
    EXPECT_EQ(sim.GetMemoryStats().hostBytes[(int)MemoryGroup::OWNER_STATE], before + late->GetHostBytes());
    sim.UpdateClumps();
    EXPECT_EQ(late->GetHostBytes(), sizeof(std::shared_ptr<DEMClumpTemplate>));
}
