// The CPU's two forms of the contact history (backend/cpu/HistoryForm.h): W floats per pair, or a
// slot per pair and a pool of the histories that are not zeros. The force model sees the same
// values either way, so a run must be the same bit for bit in both forms (and under the automatic
// choice), through re-detections, sphere-triangle hand-overs, pairs that start and stop touching, a
// host read of the contact set between calls (which makes the history dense until the next batch)
// and a user's model that sees the pairs that are apart; and so must a run that keeps every pair of
// the set in use through its detections (not only those that hand something on:
// backend/cpu/CarriedPairs.h), and a run whose set keeps every pair's A (not as runs of A's owners,
// backend/cpu/ContactARuns.h). CPU only: the GPU keeps its sets dense and whole, A per pair.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "BackendFixture.h"
#include "ForceModelTestUtil.h"
#include "MeshBuilders.h"
#include "ScratchDirTest.h"
#include "TestHelpers.h"
#include "state/SimState.h"

using namespace deme;
using namespace deme_test;

namespace {

constexpr float R = 0.006f;
constexpr double DT = 2e-5;

// Spheres dropped with sideways speeds onto a tessellated floor (a mesh) inside a walled box, with
// friction and rolling resistance: pairs touch, part and slide across triangle edges.
struct FallingBed {
    DEMSolver sim;
    std::shared_ptr<DEMTracker> grains, floor;
    size_t n = 0;
    explicit FallingBed(bool customModel) {
        sim.SetVerbosity("QUIET");
        sim.SetBackend("cpu");
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5, 0.02));
        if (customModel) declareHertzMindlinInputs(*sim.DefineContactForceModel(hertzMindlinSnippet()));
        sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.3f);
        sim.InstructBoxDomainBoundingBC("top_open", mat);
        auto mesh = sim.AddWavefrontMeshObject(gridFloor(-0.1f, -0.1f, -0.12f, 8, 0.025f, mat));
        auto type = sim.LoadSphereType((float)sphereMass(R, 2500), R, mat);
        std::vector<float3> pts =
            GridSampler(3.f * R).SampleBox(make_float3(0, 0, -0.08f), make_float3(0.07f, 0.07f, 0.03f));
        std::mt19937 rng(5);
        std::uniform_real_distribution<float> jitter(-0.3f * R, 0.3f * R);
        for (float3& p : pts) p = p + make_float3(jitter(rng), jitter(rng), jitter(rng));
        auto batch = sim.AddClumps(type, pts);
        std::vector<float3> v(pts.size());
        for (float3& x : v) x = make_float3(jitter(rng) * 100.f, jitter(rng) * 100.f, -0.5f);
        batch->SetVel(v);
        n = pts.size();
        sim.SetInitTimeStep(DT);
        sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
        sim.SetCDUpdateFreq(10);
        sim.Initialize();
        grains = sim.Track(batch);
        floor = sim.Track(mesh);
    }
};

struct Trajectory {
    std::vector<float3> pos, vel, angVel, force;
    float3 floorForce;
};

Trajectory record(const FallingBed& b) {
    Trajectory t;
    for (size_t k = 0; k < b.n; k++) {
        t.pos.push_back(b.grains->Pos(k));
        t.vel.push_back(b.grains->Vel(k));
        t.angVel.push_back(b.grains->AngVelGlobal(k));
        t.force.push_back(b.grains->ContactForce(k));
    }
    t.floorForce = b.floor->ContactForce();
    return t;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

bool same(const float3& a, const float3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

size_t differing(const Trajectory& a, const Trajectory& b) {
    size_t d = 0;
    for (size_t k = 0; k < a.pos.size(); k++)
        d += !same(a.pos[k], b.pos[k]) || !same(a.vel[k], b.vel[k]) || !same(a.angVel[k], b.angVel[k]) ||
             !same(a.force[k], b.force[k]);
    return d + !same(a.floorForce, b.floorForce);
}

class ContactHistoryForm : public ScratchDirTest {
  protected:
    // The bed in one form: 1500 steps, a contact file (a host read: the history densified), 1500 more.
    std::vector<Trajectory> run(const char* form, bool customModel, size_t& contactsBytes) {
        const ScopedEnvironmentVariable chosen("DEME_CONTACT_HISTORY", form);
        FallingBed b(customModel);
        std::vector<Trajectory> t;
        b.sim.DoDynamics(1500 * DT);
        t.push_back(record(b));
        b.sim.WriteContactFile((dir / (std::string(form) + ".csv")).string());
        b.sim.FlushOutput();
        b.sim.DoDynamics(1500 * DT);
        t.push_back(record(b));
        EXPECT_GT(b.sim.GetNumContacts(), b.n / 8) << form;  // grains landed and touch
        contactsBytes = b.sim.GetMemoryStats().host(MemoryGroup::CONTACTS);
        return t;
    }

    void checkFormsStepAlike(bool customModel) {
        size_t denseBytes, pooledBytes, autoBytes;
        const std::vector<Trajectory> dense = run("dense", customModel, denseBytes);
        const std::vector<Trajectory> pooled = run("pooled", customModel, pooledBytes);
        const std::vector<Trajectory> chosen = run("auto", customModel, autoBytes);
        // Every pair of the set in use kept through each detection, not only the pairs that hand
        // something to the next set (backend/cpu/CarriedPairs.h): the same too.
        std::vector<Trajectory> whole, aPerPair;
        {
            const ScopedEnvironmentVariable keep("DEME_KEEP_WHOLE_SET", "1");
            size_t wholeBytes;
            whole = run("auto", customModel, wholeBytes);
        }
        {
            const ScopedEnvironmentVariable perPair("DEME_CONTACT_A_PER_PAIR", "1");
            size_t perPairBytes;
            aPerPair = run("auto", customModel, perPairBytes);  // (by default the bed's keeps A as runs)
        }
        for (size_t k = 0; k < dense.size(); k++) {
            EXPECT_EQ(differing(dense[k], pooled[k]), 0u) << "part " << k;
            EXPECT_EQ(differing(dense[k], chosen[k]), 0u) << "part " << k;
            EXPECT_EQ(differing(dense[k], whole[k]), 0u) << "part " << k;
            EXPECT_EQ(differing(dense[k], aPerPair[k]), 0u) << "part " << k;
        }
        // The bed is moving (the comparison is not of grains at rest) and touches the mesh.
        EXPECT_GT(length(dense[1].vel[0]) + length(dense[1].vel[dense[1].vel.size() / 2]), 0.f);
        EXPECT_GT(length(dense[1].floorForce), 0.f);
        EXPECT_NE(denseBytes, pooledBytes);  // the two forms were taken
    }
};

}  // namespace

TEST_F(ContactHistoryForm, DenseAndPooledStepAlikeBitForBit) { checkFormsStepAlike(false); }

// A user's model sees every pair, apart or not (here Hertz-Mindlin as a snippet, which clears an
// apart pair's history itself).
TEST_F(ContactHistoryForm, DenseAndPooledStepAlikeBitForBitWithAUsersModel) { checkFormsStepAlike(true); }

namespace {

// Spheres on a lattice 0.1 % wider than their diameter, at rest, with a margin of 50 um: every
// neighbour within the margin (six per sphere), none touching: the early mixer's contact set.
size_t latticeContactsBytes(const char* form, float gap, int steps, bool aPerPair = false, bool markPersistent = false,
                            size_t* persistentPairs = nullptr) {
    const ScopedEnvironmentVariable chosen("DEME_CONTACT_HISTORY", form);
    const ScopedEnvironmentVariable perPair("DEME_CONTACT_A_PER_PAIR", aPerPair ? "1" : "0");
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    sim.SetBackend("cpu");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.2f);
    sim.InstructBoxDomainBoundingBC("all", mat);
    auto type = sim.LoadSphereType((float)sphereMass(R, 2500), R, mat);
    sim.AddClumps(type, GridSampler(2.f * R + gap).SampleBox(make_float3(0), make_float3(0.05f, 0.05f, 0.05f)));
    sim.SetInitTimeStep(DT);
    sim.SetMaxVelocity(1.f);
    sim.SetCDUpdateFreq(10);
    sim.DisableAdaptiveUpdateFreq();
    sim.Initialize();
    if (markPersistent) {
        sim.DoDynamics(DT);  // a set to mark
        sim.MarkPersistentContact();
        steps--;
    }
    sim.DoDynamics(steps * DT);
    const size_t bytes = sim.GetMemoryStats().host(MemoryGroup::CONTACTS);
    if (persistentPairs) *persistentPairs = sim.GetNumPersistentContacts();
    return bytes;
}

}  // namespace

// Where most pairs are apart the automatic choice pools the history: a bit and a sixteenth of a
// 4-byte rank a pair (12 bytes per 64 pairs) instead of the model's W = 4 floats, and no pair has a
// history to keep. Where the grains overlap (a lattice 0.1 % narrower than their diameter) every
// pair has a history after a step, and the sets installed after that keep the dense form.
TEST(ContactHistoryFormChoice, PoolsWhereMostPairsAreApartAndKeepsABedDense) {
    const size_t dense = latticeContactsBytes("dense", 0.002f * R, 5);
    const size_t pooled = latticeContactsBytes("pooled", 0.002f * R, 5);
    const size_t chosen = latticeContactsBytes("auto", 0.002f * R, 5);
    EXPECT_EQ(chosen, pooled);
    ASSERT_GT(dense, pooled);
    // The difference is 16 n - 12 ceil(n / 64) for the set's n pairs, exactly.
    auto saved = [](size_t n) { return 16 * n - 12 * ((n + 63) / 64); };
    const size_t n = (size_t)std::llround((double)(dense - pooled) / (16.0 - 12.0 / 64.0));
    const bool exact = saved(n) == dense - pooled || saved(n + 1) == dense - pooled || saved(n - 1) == dense - pooled;
    EXPECT_TRUE(exact) << dense - pooled << " bytes less, about " << n << " pairs";
    EXPECT_GT(n, 1000u);

    // Overlapping: after 25 steps (two detections after the first step) the auto run is dense.
    EXPECT_EQ(latticeContactsBytes("auto", -0.002f * R, 25), latticeContactsBytes("dense", -0.002f * R, 25));
}

TEST(ContactHistoryFormChoice, AnUnknownFormIsANamedError) {
    const std::string msg = demeErrorMessage([] { latticeContactsBytes("sparse", 0.002f * R, 1); });
    EXPECT_TRUE(contains(msg, "DEME_CONTACT_HISTORY")) << msg;
    EXPECT_TRUE(contains(msg, "sparse")) << msg;
}

// Spheres that are their owners keep A as runs (backend/cpu/ContactARuns.h): exactly 4 bytes a pair
// less than with A per pair, the set's n pairs measured as above (the dense form's 16 B a pair of
// history against the pool's).
TEST(ContactARuns, FourBytesAPairLessWhereSpheresAreTheirOwners) {
    const size_t dense = latticeContactsBytes("dense", 0.002f * R, 5);
    const size_t pooled = latticeContactsBytes("pooled", 0.002f * R, 5);
    const size_t n = (size_t)std::llround((double)(dense - pooled) / (16.0 - 12.0 / 64.0));
    ASSERT_GT(n, 1000u);
    const size_t perPair = latticeContactsBytes("pooled", 0.002f * R, 5, true);
    EXPECT_EQ(perPair - pooled, 4 * n);
}

// The CPU's steps keep no persistent flags where no pair has one and the model sets none
// (keepPersistentFlagsWhereUsed): exactly a byte a pair less than where every pair is marked
// persistent (the lattice's pairs are found by every detection, so the set is the same), and a
// host reader (the count) sees the flags.
TEST(ContactPersistentFlags, OneByteAPairLessWhereNoPairIsPersistent) {
    const size_t dense = latticeContactsBytes("dense", 0.002f * R, 5);
    const size_t pooled = latticeContactsBytes("pooled", 0.002f * R, 5);
    const size_t n = (size_t)std::llround((double)(dense - pooled) / (16.0 - 12.0 / 64.0));
    ASSERT_GT(n, 1000u);
    size_t none = 1, all = 0;
    const size_t unmarked = latticeContactsBytes("pooled", 0.002f * R, 25, false, false, &none);
    const size_t marked = latticeContactsBytes("pooled", 0.002f * R, 25, false, true, &all);
    EXPECT_EQ(none, 0u);
    EXPECT_EQ(all, n);
    EXPECT_EQ(marked - unmarked, n);
}

// The runs give every pair's A (ContactArrays::pairA), and A comes back before the runs go
// (resetIndex) or when asked (restoreA).
TEST(ContactARuns, RunsGiveEveryPairsAAndComeBackBeforeTheIndexGoes) {
    ContactArrays c;
    // Owners 0..4 as A of 2, 0, 3, 1, 0 pairs.
    c.geomB = {7, 9, 3, 5, 6, 8, 9};
    c.ownerAStart = {0, 2, 2, 5, 6, 7, 7};
    c.aAsRuns = true;
    const std::vector<bodyID_t> expected = {0, 0, 2, 2, 2, 3, 4};
    for (size_t i = 0; i < expected.size(); i++) EXPECT_EQ(c.pairA(i), expected[i]) << i;
    ContactArrays copy = c;
    copy.restoreA();
    EXPECT_FALSE(copy.aAsRuns);
    EXPECT_EQ(copy.geomA, expected);
    c.resetIndex();
    EXPECT_FALSE(c.aAsRuns);
    EXPECT_EQ(c.geomA, expected);
    EXPECT_TRUE(c.ownerAStart.empty());
}
