// Spheres that are their owners (state/SphereLayout.h): a scene whose clumps are all one sphere at
// their centre keeps no sphere offsets, centres or arms (48 bytes a sphere), and reads the owners'
// instead. Nothing of that may show: the same scene run with the full arrays
// (DEME_FULL_SPHERE_LAYOUT=1) must give the same trajectory bit for bit, on every backend, through
// the edits that switch the layout (a two-sphere clump added, then removed) and a checkpoint restart.
// The scene gives every owner at most two contacts, so that the GPU's atomic sums are exact.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(SphereLayout);

namespace {

constexpr double DT = 2e-5;
constexpr float R = 0.01f;
constexpr size_t TOWERS = 12;
constexpr size_t SPHERES = 2 * TOWERS;
constexpr size_t OFFSETS_CENTRES_ARMS = sizeof(float3) + sizeof(double3) + sizeof(float3);  // per sphere
constexpr size_t SPHERE_OWNER = sizeof(bodyID_t);  // per sphere: sphere i's owner is i
// The host's sphere id maps, which such a scene shares with its owners' (state/SphereIds.h).
constexpr size_t SPHERE_ID_MAPS = 2 * sizeof(bodyID_t);
// The owners' sphere ranges, which it does not keep (the clumps, the plane's owner and the end).
constexpr size_t SPHERE_RANGES = (SPHERES + 1 + 1) * sizeof(uint32_t);
constexpr family_t DUMBBELL_FAMILY = 4;

// Towers of two spheres on a floor, far apart, the upper one spun and pushed sideways so that it
// rolls off: every bottom sphere touches the floor and at most its upper sphere, and that one at
// most the bottom one and the floor. Friction and rolling resistance act.
struct Towers {
    DEMSolver sim;
    std::shared_ptr<DEMMaterial> mat;
    std::shared_ptr<DEMClumpBatch> grains;
    std::shared_ptr<DEMTracker> tracker;

    Towers() {
        sim.SetVerbosity("QUIET");
        mat = sim.LoadMaterial(material(1e7, 0.3, 0.6, 0.4, 0.02));
        sim.InstructBoxDomainDimension(2.0, 2.0, 1.0);
        sim.AddBCPlane(make_float3(0, 0, -0.4f), make_float3(0, 0, 1), mat);
        auto type = sim.LoadSphereType((float)sphereMass(R, 2500), R, mat);
        std::vector<float3> pts;
        for (size_t k = 0; k < TOWERS; k++) {
            const float x = -0.8f + 0.15f * (float)(k % 6), y = -0.5f + 0.3f * (float)(k / 6);
            pts.push_back(make_float3(x, y, -0.4f + R));
            pts.push_back(make_float3(x + 0.002f * (float)(k % 3), y, -0.4f + 3 * R + 0.001f));
        }
        grains = sim.AddClumps(type, pts);
        sim.SetInitTimeStep(DT);
        sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
        sim.SetCDUpdateFreq(20);
        sim.Initialize();
        tracker = sim.Track(grains);
        for (size_t k = 0; k < TOWERS; k++) {
            tracker->SetVel(make_float3(0.05f * (float)(k % 4), 0.f, 0.f), 2 * k + 1);
            tracker->SetAngVel(make_float3(0.f, 3.f * (float)(k % 5), 1.f), 2 * k + 1);
        }
    }
    size_t hostGeometry() const { return sim.GetMemoryStats().host(MemoryGroup::GEOMETRY); }
    size_t deviceGeometry() const { return sim.GetMemoryStats().device(MemoryGroup::GEOMETRY); }
};

struct Snapshot {
    std::vector<float3> pos, vel, angVel, force, torque;
};

Snapshot snapshot(const DEMTracker& t) {
    Snapshot s;
    for (size_t k = 0; k < SPHERES; k++) {
        s.pos.push_back(t.Pos(k));
        s.vel.push_back(t.Vel(k));
        s.angVel.push_back(t.AngVelGlobal(k));
        s.force.push_back(t.ContactForce(k));
        s.torque.push_back(t.ContactTorque(k));
    }
    return s;
}

bool same(const float3& a, const float3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

size_t differing(const Snapshot& a, const Snapshot& b) {
    size_t n = 0;
    for (size_t k = 0; k < a.pos.size(); k++)
        if (!same(a.pos[k], b.pos[k]) || !same(a.vel[k], b.vel[k]) || !same(a.angVel[k], b.angVel[k]) ||
            !same(a.force[k], b.force[k]) || !same(a.torque[k], b.torque[k]))
            n++;
    return n;
}

// The run both layouts make: steps, a dumbbell added (two spheres: the full layout from then on),
// steps, the dumbbell removed (one-sphere clumps only again), steps. A snapshot after each part, and
// the host's geometry bytes before and after each edit.
struct EditedRun {
    std::vector<Snapshot> snaps;
    std::vector<size_t> hostGeometry;
    size_t deviceGeometry = 0;
    float3 dumbbellRest = make_float3(0.f);
};

EditedRun runWithEdits() {
    Towers s;
    EditedRun r;
    s.sim.DoDynamics(1500 * DT);
    r.snaps.push_back(snapshot(*s.tracker));
    r.hostGeometry.push_back(s.hostGeometry());
    r.deviceGeometry = s.deviceGeometry();

    const float I = (float)(2 * 0.4 * sphereMass(R, 2500) * R * R);
    auto dumbbell = s.sim.LoadClumpType((float)(2 * sphereMass(R, 2500)), make_float3(I, 3 * I, 3 * I), {R, R},
                                        {make_float3(-R, 0, 0), make_float3(R, 0, 0)}, s.mat);
    auto added = s.sim.AddClumps(dumbbell, {make_float3(0.5f, 0.6f, -0.4f + R + 0.002f)});
    added->SetFamily(DUMBBELL_FAMILY);
    auto tracked = s.sim.Track(added);
    s.sim.UpdateClumps();
    r.hostGeometry.push_back(s.hostGeometry());
    s.sim.DoDynamics(1500 * DT);
    r.snaps.push_back(snapshot(*s.tracker));
    r.dumbbellRest = tracked->Pos();

    EXPECT_EQ(s.sim.RemoveClumpsInFamily(DUMBBELL_FAMILY), 1u);
    r.hostGeometry.push_back(s.hostGeometry());
    s.sim.DoDynamics(1500 * DT);
    r.snaps.push_back(snapshot(*s.tracker));
    return r;
}

}  // namespace

// The arrays are gone (48 bytes a sphere on the host exactly, the 4 of its owner's index, and the 8
// of the sphere id maps and the owners' sphere ranges; at least 52 on a GPU), and the run is the full layout's bit for
// bit, through the edits that switch the layout and back.
DEME_BACKEND_TEST(SphereLayout, OneSphereClumpsKeepNoOffsetsCentresOrArmsAndStepAlike) {
    EditedRun full;
    {
        const ScopedEnvironmentVariable forced("DEME_FULL_SPHERE_LAYOUT", "1");
        full = runWithEdits();
    }
    const EditedRun owners = runWithEdits();

    EXPECT_EQ(full.hostGeometry[0] - owners.hostGeometry[0],
              SPHERES * (OFFSETS_CENTRES_ARMS + SPHERE_OWNER + SPHERE_ID_MAPS) + SPHERE_RANGES);
    if (onGpu()) {
        EXPECT_GE(full.deviceGeometry - owners.deviceGeometry, SPHERES * (OFFSETS_CENTRES_ARMS + SPHERE_OWNER));
    } else {
        EXPECT_EQ(owners.deviceGeometry, 0u);
    }
    // A two-sphere clump: the full arrays for every sphere; gone with it, the arrays go too.
    EXPECT_GE(owners.hostGeometry[1], owners.hostGeometry[0] + SPHERES * OFFSETS_CENTRES_ARMS);
    // (The other arrays keep the capacity the insertion gave them.)
    EXPECT_GE(owners.hostGeometry[1] - owners.hostGeometry[2], SPHERES * OFFSETS_CENTRES_ARMS);
    EXPECT_GE(full.hostGeometry[2] - owners.hostGeometry[2], SPHERES * OFFSETS_CENTRES_ARMS);

    ASSERT_EQ(full.snaps.size(), owners.snaps.size());
    for (size_t i = 0; i < full.snaps.size(); i++)
        EXPECT_EQ(differing(full.snaps[i], owners.snaps[i]), 0u) << "spheres that differ after part " << i;
    EXPECT_TRUE(same(full.dumbbellRest, owners.dumbbellRest));
    // The scene did something: upper spheres rolled off their towers, and the dumbbell fell onto
    // the floor and bounces on it (dropped from 2 mm; not through it).
    size_t fell = 0;
    for (size_t k = 0; k < TOWERS; k++) fell += owners.snaps.back().pos[2 * k + 1].z < -0.4f + 2 * R;
    EXPECT_GT(fell, 0u);
    EXPECT_LT(owners.dumbbellRest.z, -0.4f + R + 0.0015f);
    EXPECT_GT(owners.dumbbellRest.z, -0.4f + R - 1e-4f);
}

// A checkpoint of spheres that are their owners holds no offsets, centres or arms, and a restart
// from it continues bit for bit.
DEME_BACKEND_TEST(SphereLayout, CheckpointRestartsBitForBit) {
    Towers whole;
    whole.sim.DoDynamics(1000 * DT);
    const std::string path = (scratchDir() / "towers.chk").string();
    whole.sim.WriteCheckpoint(path);
    whole.sim.DoDynamics(1000 * DT);

    Towers restarted;
    restarted.sim.ReadCheckpoint(path);
    EXPECT_EQ(restarted.hostGeometry(), whole.hostGeometry());
    restarted.sim.DoDynamics(1000 * DT);
    EXPECT_EQ(differing(snapshot(*whole.tracker), snapshot(*restarted.tracker)), 0u);
}
