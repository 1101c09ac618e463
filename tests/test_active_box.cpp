// The active box (docs/active-box.md): dormant grains (a fixed family with no contacts among fixed
// families) are registered once and not re-binned; the pairs found with that cache are exactly a
// full search's, less the dormant-dormant and dormant-still-wall pairs that move nothing; dormant
// grains hold up active ones at the Hertzian static overlap; and the motion of the active grains is
// the same bit for bit with the cache as without it.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "BackendFixture.h"
#include "DetectionScenes.h"
#include "TestHelpers.h"
#include "backend/cpu/ContactDetector.h"
#include "kinematics/BinGridSizing.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(ActiveBox);

namespace {

std::set<std::pair<bodyID_t, bodyID_t>> detectPairs(ContactDetector& det, const SimState& s, const BinGrid& grid,
                                                     double margin, const FamilyRules& rules, const float* extra) {
    DetectedContacts found;
    double binning = 0.0, search = 0.0;
    det.detect(s, grid, margin, rules.contactMask(), extra, found, binning, search);
    std::set<std::pair<bodyID_t, bodyID_t>> got;
    for (size_t i = 0; i < found.size(); i++) {
        if (i > 0) {  // sorted by (A, B), no duplicates: what history mapping needs
            EXPECT_LT(contactKey(found.geomA[i - 1], found.geomB[i - 1]), contactKey(found.geomA[i], found.geomB[i]));
        }
        got.insert({found.geomA[i], found.geomB[i]});
    }
    return got;
}

// The brute-force answer less the pairs the cache leaves out on purpose: a dormant sphere with a
// still wall (dormant-dormant pairs are masked, so brute force has none).
std::set<std::pair<bodyID_t, bodyID_t>> expectedPairs(const SimState& s, double margin, const FamilyRules& rules,
                                                      const float* extra, const uint8_t* dormant) {
    auto all = bruteForce(s, margin, rules.contactMask(), extra);
    std::set<std::pair<bodyID_t, bodyID_t>> out;
    for (const auto& p : all) {
        const bool dormantA = dormant[s.owners.family[s.spheres.owner[p.first]]] != 0;
        if (dormantA && p.second >= s.analyticalIdBase()) continue;
        out.insert(p);
    }
    return out;
}

}  // namespace

TEST(ActiveBoxDetection, DormantCacheFindsExactlyTheFullSearchsPairs) {
    FamilyRules rules;
    rules.motion(2).fixed = true;   // family 2 is dormant: fixed, ...
    rules.setContact(2, 2, false);  // ... no contacts among its grains
    float extra[NUM_FAMILIES] = {};
    extra[1] = 2e-4f;  // walls
    extra[2] = 1e-4f;  // dormant grains reach further: the cache's search box must grow by it
    uint8_t dormant[NUM_FAMILIES], prescribed[NUM_FAMILIES];
    rules.dormantFamilies(dormant);
    rules.prescribedFamilies(prescribed);
    ASSERT_EQ(dormant[2], 1);
    ASSERT_EQ(dormant[0] + dormant[1], 0);
    for (unsigned seed : {1u, 2u}) {
        const Scene scene = randomScene(seed, 1500);
        SimState s = detectionState(scene, "ActiveBox");
        const BinGrid grid = makeBinGrid(s, 0.0015);
        ContactDetector det;
        det.setFamilies(dormant, prescribed, s);
        for (double margin : {0.0, 1e-4, 3e-4}) {
            const auto expected = expectedPairs(s, margin, rules, extra, dormant);
            EXPECT_GT(expected.size(), 500u);
            EXPECT_EQ(detectPairs(det, s, grid, margin, rules, extra), expected) << "seed " << seed << " margin " << margin;
        }
        // Built once for three margins: the registry is by centre bin, the margin is the search's.
        EXPECT_EQ(det.dormantCache().rebuilds(), 1u);
        EXPECT_LT(det.dormantCache().moving().size(), s.spheres.size());
        EXPECT_GT(det.dormantCache().moving().size(), 0u);
        // A family change (a grain wakes up, another falls dormant) rebuilds it, once.
        ASSERT_TRUE(wakeOneAndFreezeOne(s, 2, 0));
        for (double margin : {1e-4, 2e-4})
            EXPECT_EQ(detectPairs(det, s, grid, margin, rules, extra), expectedPairs(s, margin, rules, extra, dormant));
        EXPECT_EQ(det.dormantCache().rebuilds(), 2u);
        // A wall that moves and reaches dormant grains: no cache (every pair searched, as without it).
        s.owners.vel[s.analytical.owner[0]] = make_float3(0, 0, 0.1f);
        det.setFamilies(dormant, prescribed, s);
        EXPECT_EQ(detectPairs(det, s, grid, 1e-4, rules, extra), bruteForce(s, 1e-4, rules.contactMask(), extra));
        EXPECT_EQ(det.dormantCache().rebuilds(), 2u);
    }
}

namespace {

constexpr double R = 0.01, RHO = 2500, E = 1e8, NU = 0.3, G = 9.81;

// A 5 x 5 square lattice of touching spheres (family 1) and, on the middle one, one sphere of
// family 0 placed at the Hertzian static overlap. `dormant`: family 1 fixed and without contacts
// among itself (the cache serves); otherwise family 1 is fixed with its contacts on (full search).
struct Stack {
    DEMSolver sim;
    std::shared_ptr<DEMClumpBatch> top, bed;
    double restZ = 0.0;
    Stack(bool dormant, const std::string& backend = "") {
        sim.SetVerbosity("QUIET");
        if (!backend.empty()) sim.SetBackend(backend);
        auto mat = sim.LoadMaterial(material(E, NU, 0.3, 0.5));
        sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.2f);
        auto tmpl = sim.LoadSphereType((float)sphereMass(R, RHO), (float)R, mat);
        std::vector<float3> bed;
        for (int i = -2; i <= 2; i++)
            for (int j = -2; j <= 2; j++) bed.push_back(make_float3((float)(2 * R * i), (float)(2 * R * j), 0.f));
        this->bed = sim.AddClumps(tmpl, bed);
        this->bed->SetFamily(1);
        // Static overlap of two equal spheres (Hertz): m g = 4/3 E* sqrt(R/2) d^1.5, E* = E / (2 (1 - nu^2)).
        const double m = sphereMass(R, RHO);
        const double d = std::pow(m * G / (4.0 / 3.0 * effectiveModulus(E, NU) * std::sqrt(R / 2)), 2.0 / 3.0);
        restZ = 2 * R - d;
        top = sim.AddClumps(tmpl, {make_float3(0.f, 0.f, (float)restZ)});
        sim.SetFamilyFixed(1);
        if (dormant) sim.DisableContactBetweenFamilies(1, 1);
        sim.SetInitTimeStep(1e-5);
        sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-G));
        sim.SetSynchronousContactDetection(true);
    }
};

}  // namespace

// Dormant grains hold up an active one: it stays at the static Hertzian overlap (within 1 % of the
// overlap, about 1.6e-7 m of 1.6e-5 m), on either backend.
DEME_BACKEND_TEST(ActiveBox, DormantGrainsHoldUpAnActiveGrainAtTheHertzOverlap) {
    Stack st(true);
    st.sim.Initialize();
    auto tr = st.sim.Track(st.top);
    auto bedTr = st.sim.Track(st.bed);
    const float3 under = bedTr->Pos(12);  // the middle one, (0, 0)
    st.sim.DoDynamics(0.1);
    const double overlap = 2 * R - st.restZ;
    EXPECT_NEAR(tr->Pos().z, st.restZ, 0.01 * overlap);
    EXPECT_NEAR(tr->Pos().x, 0.0, 1e-9);
    EXPECT_LT(std::fabs(tr->Vel().z), 1e-3);
    EXPECT_EQ(st.sim.GetNumContacts(), 1u);  // the one active-dormant pair; dormant pairs are not resolved
    // The dormant grain under it carries its weight (a dormant grain's contact forces are still
    // summed, though it is not integrated); one without contacts carries nothing.
    const double weight = sphereMass(R, RHO) * G;
    EXPECT_NEAR(bedTr->ContactForce(12).z, -weight, 0.01 * weight);
    EXPECT_EQ(bedTr->ContactForce(0).z, 0.f);  // a corner
    EXPECT_EQ(bedTr->Pos(12).z, under.z);      // not moved by it
    EXPECT_EQ(bedTr->Vel(12).z, 0.f);
}

// The active grains' motion is the same bit for bit whether the dormant grains are cached (their
// contacts among each other off) or searched with the rest (contacts on: forces between two fixed
// grains move nothing), and whether the steps leave them out or not. A grain dropped from 1 mm
// bounces on the bed. On the CPU the sums are in a fixed order; on the GPU too for this grain: it
// touches the middle bed grain only (2.2 mm off its top, 26.9 mm from the next one's centre), so its
// force is one contact's, whatever the order of the atomics elsewhere.
DEME_BACKEND_TEST(ActiveBox, ActiveMotionIsTheSameBitForBitWithTheCache) {
    float3 pos[2], vel[2];
    for (int dormant = 0; dormant < 2; dormant++) {
        Stack st(dormant == 1);
        st.sim.Initialize();
        auto tr = st.sim.Track(st.top);
        tr->SetPos(make_float3(0.002f, 0.001f, (float)(2 * R + 1e-3)));
        st.sim.DoDynamics(0.05);
        pos[dormant] = tr->Pos();
        vel[dormant] = tr->Vel();
    }
    EXPECT_LT(pos[0].z, 2 * R);  // it reached the bed
    EXPECT_EQ(pos[0].x, pos[1].x);
    EXPECT_EQ(pos[0].y, pos[1].y);
    EXPECT_EQ(pos[0].z, pos[1].z);
    EXPECT_EQ(vel[0].x, vel[1].x);
    EXPECT_EQ(vel[0].z, vel[1].z);
}
