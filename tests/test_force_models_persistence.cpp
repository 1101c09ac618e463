// Persistent contacts (DEMSolver::MarkPersistentContact and its family variants): detection re-inserts
// a persistent pair it no longer finds, keeping the contact set sorted and the pair's wildcards, in
// synchronous and asynchronous detection, until the model or the user releases it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "BackendFixture.h"
#include "BondedCompression.h"
#include "ForceModelTestUtil.h"
#include "backend/cpu/HistoryForm.h"
#include "DetectedPairs.h"
#include "backend/cpu/HistoryMapping.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(ForceModelPersistence);

namespace {

// Four spheres (owners 0..3, families 0, 0, 1, 1), one wildcard per contact.
SimState fourSpheres() {
    SimState s;
    s.spheres.owner = {0, 1, 2, 3};
    s.owners.voxel.assign(4, 0);  // four owners (installing a set indexes each owner's contacts)
    s.owners.family = {0, 0, 1, 1};
    s.numWildcards = 1;
    return s;
}

void setContacts(SimState& s, const std::vector<std::pair<bodyID_t, bodyID_t>>& pairs,
                 const std::vector<float>& wildcards, const std::vector<uint8_t>& persistent) {
    ContactArrays& c = s.contacts;
    c.geomA.clear();
    c.geomB.clear();
    for (const auto& p : pairs) c.geomA.push_back(p.first), c.geomB.push_back(p.second);
    c.wildcards = wildcards;
    c.persistent = persistent;
    c.meshState.assign(pairs.size(), 0);
}

}  // namespace

// History mapping alone: persistent pairs missing from a detection are merged back in key order with
// their wildcards and flag; a non-persistent pair that was not detected is gone; surviving pairs keep
// their wildcards; new pairs start at 0, or at the value set for their families. The CPU's code on
// its own, no simulation: a plain test (the GPU's merge against these rules: CudaPersistentMerge.*).
// Both forms of the CPU's history (backend/cpu/HistoryForm.h), each set read back densified.
TEST(PersistentHistoryMapping, KeepsPersistentPairsSorted) {
    for (const char* form : {"dense", "pooled"}) {
        SCOPED_TRACE(form);
        const ScopedEnvironmentVariable chosen("DEME_CONTACT_HISTORY", form);
        SimState s = fourSpheres();
        s.wildcards.contactInit.push_back({0, 1, 0, 7.f});  // contacts between families 0 and 1 start at 7
        setContacts(s, {{0, 1}, {0, 3}, {1, 2}, {2, 3}}, {1.f, 2.f, 3.f, 4.f}, {1, 1, 0, 1});
        DetectedContacts fresh = detected({{0, 2}, {1, 2}, {1, 3}});
        installDetectedContacts(s, fresh, true);
        const ContactArrays& c = s.contacts;
        EXPECT_EQ(c.historyPooled(1), std::string(form) == "pooled");
        const std::vector<bodyID_t> A = {0, 0, 0, 1, 1, 2}, B = {1, 2, 3, 2, 3, 3};
        EXPECT_EQ(c.geomA, A);
        EXPECT_EQ(c.geomB, B);
        // (0,1) kept: 1; (0,2) new, families 0-1: 7; (0,3) kept: 2; (1,2) survived: 3; (1,3) new: 7;
        // (2,3) kept: 4. The non-persistent (1,2) survived because it was detected.
        SimState read = s;
        densifyHistory(read);
        EXPECT_EQ(read.contacts.wildcards, (std::vector<float>{1.f, 7.f, 2.f, 3.f, 7.f, 4.f}));
        EXPECT_EQ(c.persistent, (std::vector<uint8_t>{1, 0, 1, 0, 0, 1}));
        // No step has stored forces for the new set yet.
        EXPECT_EQ(c.stored.count(), 0u);
        // The detection's arrays, which took the old set's ids in the swap, hold nothing afterwards (a
        // copy of every pair kept between detections otherwise: docs/memory.md).
        EXPECT_EQ(fresh.bytes(), 0u);

        // Released pairs are dropped at the next detection that does not find them (the old set read
        // from the pool where it is pooled).
        s.contacts.persistent = {0, 0, 1, 0, 0, 0};
        DetectedContacts none;
        installDetectedContacts(s, none, true);
        EXPECT_EQ(s.contacts.geomA, (std::vector<bodyID_t>{0}));
        EXPECT_EQ(s.contacts.geomB, (std::vector<bodyID_t>{3}));
        densifyHistory(s);
        EXPECT_EQ(s.contacts.wildcards, (std::vector<float>{2.f}));
    }
}

namespace {

// Two bonded spheres (the bonded model of demos/BondedCompression.h with an unbreakable bond), one
// driven 5 mm away along the bond in 0.05 s, far beyond any margin: the bond still pulls with
// k * stretch, because the pair stays in the contact set. After RemovePersistentContact the pair
// leaves the set at the next detection: no force.
// Spheres of radius r: `held` (family 1, fixed) at the origin, `driven` (family 2) at x = gap,
// moving away along x at 0.1 m/s, and a few fixed ones around (family 3), so that detected pairs
// surround theirs; a step of 10 us, detection every 5 steps. Returns `driven`.
std::shared_ptr<DEMClumpBatch> addHeldAndDrivenPair(DEMSolver& sim, const std::shared_ptr<DEMMaterial>& mat, float r,
                                                    float gap) {
    sim.SetVerbosity("QUIET");
    sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.1f);
    auto tmpl = sim.LoadSphereType(1e-5f, r, mat);
    auto others = sim.AddClumps(tmpl, {make_float3(-0.02f, 0, 0), make_float3(-0.02f, 2.1f * r, 0),
                                       make_float3(0.03f, 0.01f, 0), make_float3(0.03f, 0.01f, 2.05f * r)});
    auto held = sim.AddClumps(tmpl, {make_float3(0, 0, 0)});
    auto driven = sim.AddClumps(tmpl, {make_float3(gap, 0, 0)});
    others->SetFamily(3);
    sim.SetFamilyFixed(3);
    held->SetFamily(1);
    driven->SetFamily(2);
    sim.SetFamilyFixed(1);
    sim.SetFamilyPrescribedLinVel(2, "0.1", "0", "0");
    for (unsigned int f = 1; f <= 3; f++) sim.SetFamilyExtraMargin(f, 0.1f * r);
    sim.SetInitTimeStep(1e-5);
    sim.SetCDUpdateFreq(5);
    return driven;
}

void checkPersistentPairSurvives(bool async) {
    const float r = 1e-3f, k = 100.f;
    DEMSolver sim;
    auto mat = sim.LoadMaterial({{"kb", k}, {"cb", 0.0}});
    bonded_demo::useBondedModel(sim);
    auto driven = addHeldAndDrivenPair(sim, mat, r, 2 * r);
    sim.SetSynchronousContactDetection(!async);
    sim.Initialize();
    sim.SetSphereWildcardValue("strength", 0, std::vector<float>(6, 1e9f));
    sim.MarkFamilyPersistentContact(1, 2);
    sim.SetFamilyContactWildcardValue(1, 2, "bonded", 1.f);
    ASSERT_EQ(sim.GetNumPersistentContacts(), 1u);
    auto tr = sim.Track(driven);
    for (int i = 0; i < 50; i++) {
        sim.DoDynamics(1e-3);
        // The last step's force came from the position before that step (0.1 m/s x 1e-5 s earlier).
        const double stretch = tr->Pos().x - 1e-6 - 2.0 * r;
        EXPECT_NEAR(tr->ContactForce().x, -k * stretch, 1e-3 * k * stretch) << "t = " << sim.GetSimTime();
    }
    EXPECT_GT(tr->Pos().x - 2 * r, 0.004);
    sim.RemoveFamilyPersistentContactEither(2);
    EXPECT_EQ(sim.GetNumPersistentContacts(), 0u);
    sim.DoDynamics(1e-3);  // n_max is 5 steps: detection has run
    EXPECT_EQ(tr->ContactForce().x, 0.f);
}

}  // namespace

// On the GPU: detection there merges the persistent pair back in (DeviceHistoryMapping), in
// both detection modes, and the host's Mark/Remove calls reach the device set.
DEME_BACKEND_TEST(ForceModelPersistence, PersistentPairSurvivesDetection) { checkPersistentPairSurvives(false); }
DEME_BACKEND_TEST(ForceModelPersistence, PersistentPairSurvivesAsyncDetection) { checkPersistentPairSurvives(true); }

// The built-in model sets no flag, so its sets keep flags only while a pair has one (1 B a pair
// otherwise, on both backends): a pair the host marks persistent survives detections with its
// spheres far apart, and once released leaves the set.
DEME_BACKEND_TEST(ForceModelPersistence, ABuiltInModelsSetKeepsTheHostsFlagsOnly) {
    const float r = 1e-3f;
    DEMSolver sim;
    auto mat = sim.LoadMaterial({{"E", 1e7}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.3}});
    addHeldAndDrivenPair(sim, mat, r, 2.05f * r);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.SetSynchronousContactDetection(true);
    sim.Initialize();
    sim.DoDynamics(1e-5);
    EXPECT_EQ(sim.GetNumPersistentContacts(), 0u);
    sim.MarkFamilyPersistentContact(1, 2);
    ASSERT_EQ(sim.GetNumPersistentContacts(), 1u);
    sim.DoDynamics(0.05);  // 5 mm apart: no detection finds the pair
    EXPECT_EQ(sim.GetNumPersistentContacts(), 1u);
    sim.RemoveFamilyPersistentContactEither(2);
    EXPECT_EQ(sim.GetNumPersistentContacts(), 0u);
    sim.DoDynamics(1e-3);
    EXPECT_EQ(sim.GetNumPersistentContacts(), 0u);
}
