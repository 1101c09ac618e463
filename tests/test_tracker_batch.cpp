// DEMTracker's batch forms against its per-owner calls, on a batch placed at random so that the
// engine's storage order differs from the user's; and the all-or-nothing batch setters.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

namespace {

// n spheres, one per cell of a 20^3 grid of 0.05 m cells picked at random: no contacts.
std::vector<float3> scatteredPoints(size_t n, unsigned seed) {
    std::vector<int> cells(20 * 20 * 20);
    std::iota(cells.begin(), cells.end(), 0);
    std::shuffle(cells.begin(), cells.end(), std::mt19937(seed));
    std::vector<float3> pts;
    for (size_t i = 0; i < n; i++) {
        const int c = cells[i];
        pts.push_back(make_float3((c % 20 + 0.5f) * 0.05f - 0.5f, ((c / 20) % 20 + 0.5f) * 0.05f - 0.5f,
                                  (c / 400 + 0.5f) * 0.05f - 0.5f));
    }
    return pts;
}

struct BatchScene {
    DEMSolver sim;
    std::shared_ptr<DEMClumpBatch> first, second;
    std::vector<float3> pts;
    explicit BatchScene(size_t n = 300, size_t m = 40) : pts(scatteredPoints(n + m, 7)) {
        sim.SetVerbosity("QUIET");
        auto mat = sim.LoadMaterial(material(1e8, 0.3, 0.5, 0.5));
        sim.InstructBoxDomainDimension(2, 2, 2);
        auto tmpl = sim.LoadSphereType((float)sphereMass(0.01, 1000), 0.01f, mat);
        first = sim.AddClumps(tmpl, std::vector<float3>(pts.begin(), pts.begin() + n));
        second = sim.AddClumps(tmpl, std::vector<float3>(pts.begin() + n, pts.end()));
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(-1.f, 1.f);
        std::vector<float3> w(n);
        std::vector<float4> q(n);
        for (size_t i = 0; i < n; i++) {
            w[i] = make_float3(u(rng), u(rng), u(rng));
            const float4 r = make_float4(u(rng), u(rng), u(rng), u(rng));
            const float l = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z + r.w * r.w);
            q[i] = make_float4(r.x / l, r.y / l, r.z / l, r.w / l);
        }
        first->SetAngVel(w);
        first->SetOriQ(q);
        first->SetVel(make_float3(0.1f, 0, 0));
        sim.SetInitTimeStep(1e-5);
        sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
        sim.Initialize();
    }
};

void expectEqual(const float3& a, const float3& b) {
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.z, b.z);
}

}  // namespace

TEST(TrackerBatch, EqualsThePerOwnerCallsInUserOrder) {
    BatchScene s;
    s.sim.DoDynamics(1e-3);
    auto ta = s.sim.Track(s.first), tb = s.sim.Track(s.second);
    const auto pos = ta->Positions(), vel = ta->Velocities(), w = ta->AngularVelocities();
    const auto f = ta->ContactForces(), t = ta->ContactTorques();
    const auto q = ta->OriQs();
    ASSERT_EQ(pos.size(), ta->GetNumOwners());
    for (size_t i = 0; i < pos.size(); i++) {
        expectEqual(pos[i], ta->Pos(i));
        expectEqual(vel[i], ta->Vel(i));
        expectEqual(w[i], ta->AngVelGlobal(i));
        expectEqual(f[i], ta->ContactForce(i));
        expectEqual(t[i], ta->ContactTorque(i));
        EXPECT_EQ(q[i].w, ta->OriQ(i).w);
        EXPECT_EQ(q[i].x, ta->OriQ(i).x);
    }
    // In the order the user added them: the first batch moved by v t from its input places.
    for (size_t i = 0; i < pos.size(); i++) {
        EXPECT_NEAR(pos[i].x, s.pts[i].x + 0.1 * s.sim.GetSimTime(), 1e-6);
        EXPECT_NEAR(pos[i].y, s.pts[i].y, 1e-6);
    }
    // The second batch's rows follow its own input, and the buffer form fills the same values.
    std::vector<float3> buf(tb->GetNumOwners());
    tb->Positions(buf.data());
    for (size_t i = 0; i < buf.size(); i++) {
        expectEqual(buf[i], tb->Pos(i));
        EXPECT_NEAR(buf[i].z, s.pts[300 + i].z, 1e-6);
    }
}

TEST(TrackerBatch, SettersApplyAllOrNothing) {
    BatchScene s;
    auto ta = s.sim.Track(s.first);
    std::vector<float3> moved = ta->Positions();
    for (auto& p : moved) p.z += 0.01f;
    ta->SetPositions(moved);
    for (size_t i = 0; i < moved.size(); i++) EXPECT_NEAR(ta->Pos(i).z, moved[i].z, 1e-6);
    std::vector<float3> v(moved.size(), make_float3(0, 0, 1));
    ta->SetVelocities(v.data());
    expectEqual(ta->Vel(17), make_float3(0, 0, 1));

    const auto before = ta->Positions();
    auto bad = before;
    bad.back() = make_float3(9, 0, 0);
    EXPECT_NE(demeErrorMessage([&] { ta->SetPositions(bad); })
                  .find("DEMTracker::SetPositions: position row 299 (9.000000, 0.000000, 0.000000) is outside the "
                        "simulation domain"),
              std::string::npos);
    const auto after = ta->Positions();
    for (size_t i = 0; i < after.size(); i++) expectEqual(after[i], before[i]);
    bad.back() = make_float3(std::nanf(""), 0, 0);
    EXPECT_NE(demeErrorMessage([&] { ta->SetVelocities(bad); }).find("must be finite"), std::string::npos);
    expectEqual(ta->Vel(299), make_float3(0, 0, 1));
    EXPECT_EQ(demeErrorMessage([&] { ta->SetPositions(std::vector<float3>(3)); }),
              "DEMTracker::SetPositions: got 3 positions for 300 owners");
}

TEST(TrackerBatch, BeforeInitializeIsAnError) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e8, 0.3, 0.5, 0.5));
    sim.InstructBoxDomainDimension(1, 1, 1);
    auto batch = sim.AddClumps(sim.LoadSphereType(1.f, 0.01f, mat), {make_float3(0, 0, 0)});
    auto tr = sim.Track(batch);
    EXPECT_EQ(demeErrorMessage([&] { tr->Velocities(); }), "DEMTracker::Velocities: the solver is not initialized yet");
}
