// Contact detection against an O(N^2) brute-force search, exactly, and the physics' independence
// from how often and on how many threads detection and forces run.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "BackendFixture.h"
#include "DetectionScenes.h"
#include "TestHelpers.h"
#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "dynamics/KinematicCache.h"
#include "backend/cpu/ContactDetector.h"
#include "kinematics/BinGridSizing.h"
#include "physics/ContactGeometry.h"
#include "physics/RigidBody.h"
#include "runtime/FamilyRules.h"

using namespace deme;
using namespace deme_test;


TEST(ContactDetection, MatchesBruteForceExactly) {
    const DetectionRules dr;
    const FamilyRules& rules = dr.rules;
    const float* extra = dr.extra;
    int cases = 0;
    for (unsigned seed : {1u, 2u, 3u}) {
        const Scene scene = randomScene(seed, 1500);
        SimState s = detectionState(scene, "ContactDetection");
        // Bins smaller than the largest spheres, so that many spheres span several bins.
        for (double binSize : {0.0015, 0.004, 0.0}) {
            const BinGrid grid = makeBinGrid(s, binSize);
            for (double margin : {0.0, 1e-4}) {
                ContactDetector det;
                // Twice with one detector: the first detection keeps each thread's A ids as runs
                // (it expects six pairs per sphere), the second as one per pair where the first
                // found fewer pairs than spheres (ContactDetector.h, ThreadPairs).
                for (int pass = 0; pass < 2; pass++) {
                    DetectedContacts found;
                    double binning = 0.0, search = 0.0;
                    det.detect(s, grid, margin, rules.contactMask(), extra, found, binning, search);
                    std::set<std::pair<bodyID_t, bodyID_t>> got;
                    for (size_t i = 0; i < found.size(); i++) {
                        if (i > 0) {  // sorted by (A, B), no duplicates
                            ASSERT_LT(contactKey(found.geomA[i - 1], found.geomB[i - 1]),
                                      contactKey(found.geomA[i], found.geomB[i]));
                        }
                        got.insert({found.geomA[i], found.geomB[i]});
                    }
                    const auto expected = bruteForce(s, margin, rules.contactMask(), extra);
                    EXPECT_GT(expected.size(), 500u);
                    EXPECT_EQ(got, expected) << "seed " << seed << ", bin " << binSize << ", margin " << margin
                                             << ", detection " << pass + 1;
                    cases++;
                }
            }
        }
    }
    EXPECT_EQ(cases, 36);
}

// Spheres are registered by their centres where none reaches beyond 3/4 of a bin
// (kinematics/DetectionRules.h, centreReachFor), by their boxes otherwise, in a sheared cell and with
// DEME_BIN_BY_BOXES=1; both find exactly the brute force's pairs, and by centre each sphere is one
// bin entry.
TEST(ContactDetection, SpheresByCentreFindTheSamePairsWithOneEntryEach) {
    const DetectionRules dr;
    const Scene scene = randomScene(5, 1500);
    SimState s = detectionState(scene, "ContactDetection");
    const float largest = *std::max_element(s.spheres.radius.begin(), s.spheres.radius.end());
    const double margin = 1e-4;
    const double reach = (double)largest + margin + (double)*std::max_element(dr.extra, dr.extra + NUM_FAMILIES);
    const BinGrid coarse = makeBinGrid(s, 0.004), fine = makeBinGrid(s, 0.0015);
    ASSERT_GE(0.75 * coarse.size, reach);
    ASSERT_LT(0.75 * fine.size, reach);
    EXPECT_DOUBLE_EQ(centreReachFor(coarse, margin, dr.extra, largest), reach);
    EXPECT_EQ(centreReachFor(fine, margin, dr.extra, largest), 0.0);
    BinGrid sheared = coarse;
    sheared.shear = 1u;
    EXPECT_EQ(centreReachFor(sheared, margin, dr.extra, largest), 0.0);
    // A family's extra margin counts in the reach: enough of it and the boxes are registered.
    float extra[NUM_FAMILIES];
    std::copy(dr.extra, dr.extra + NUM_FAMILIES, extra);
    extra[7] = 0.002f;
    EXPECT_EQ(centreReachFor(coarse, margin, extra, largest), 0.0);

    const auto expected = bruteForce(s, margin, dr.rules.contactMask(), dr.extra);
    ASSERT_GT(expected.size(), 500u);
    auto detectWith = [&](const char* byBoxes, size_t& bytes) {
        const ScopedEnvironmentVariable registration("DEME_BIN_BY_BOXES", byBoxes);
        ContactDetector det;
        DetectedContacts found;
        double binning = 0.0, search = 0.0;
        det.detect(s, coarse, margin, dr.rules.contactMask(), dr.extra, found, binning, search);
        bytes = det.bytes();
        std::set<std::pair<bodyID_t, bodyID_t>> got;
        for (size_t i = 0; i < found.size(); i++) got.insert({found.geomA[i], found.geomB[i]});
        EXPECT_EQ(got.size(), found.size()) << "a pair reported twice";
        return got;
    };
    size_t byCentre = 0, byBoxes = 0;
    EXPECT_EQ(detectWith("0", byCentre), expected);
    EXPECT_EQ(detectWith("1", byBoxes), expected);
    // One entry a sphere by centre, several by boxes, whose boxes span bins (the bins' starts and
    // the threads' lists are the same in both): at least two entries a sphere fewer here.
    EXPECT_GE(byBoxes, byCentre + 2 * s.spheres.size() * sizeof(uint32_t));
}

// The bins of one detection are kept for the next where they are small, and let go at its end
// where they are larger than the detector keeps (a large scene's steps between detections hold
// none); the pairs are the same either way, and so are those of the next detection.
TEST(ContactDetection, LargeBinsAreLetGoAfterEachDetection) {
    const DetectionRules dr;
    const Scene scene = randomScene(4, 1500);
    SimState s = detectionState(scene, "ContactDetection");
    const BinGrid grid = makeBinGrid(s, 0.0);
    ContactDetector keeping, releasing;
    releasing.keepBinsUpTo(0);
    for (int round = 0; round < 2; round++) {
        DetectedContacts kept, released;
        double binning = 0.0, search = 0.0;
        keeping.detect(s, grid, 1e-4, dr.rules.contactMask(), dr.extra, kept, binning, search);
        releasing.detect(s, grid, 1e-4, dr.rules.contactMask(), dr.extra, released, binning, search);
        ASSERT_GT(kept.size(), 500u);
        EXPECT_EQ(kept.geomA, released.geomA);
        EXPECT_EQ(kept.geomB, released.geomB);
        EXPECT_GT(keeping.bytes(), 1500 * sizeof(uint32_t));  // entries and bins' starts
        EXPECT_LT(releasing.bytes(), 1500u);                  // the per-thread lists' headers only
    }
}

namespace {

// A small granular column poured onto a floor; returns every clump's final position and velocity.
std::vector<float> runPour(unsigned int cdFreq, unsigned int threads) {
    DEMSolver sim;
    sim.SetBackend("cpu");  // the CPU's threads are under test, bit for bit
    sim.SetVerbosity("QUIET");
    sim.SetCPUThreads(threads);
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.4, 0.5, 0.01));
    sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.2f);
    sim.InstructBoxDomainBoundingBC("top_open", mat);
    auto tmpl = sim.LoadClumpType(2e-3f, make_float3(1e-8f, 1.2e-8f, 1.4e-8f), {0.003f, 0.0025f},
                                  {make_float3(0.001f, 0, 0), make_float3(-0.002f, 0, 0)}, mat);
    auto pts = HCPSampler(0.0095f).SampleBox(make_float3(0, 0, 0), make_float3(0.04f, 0.04f, 0.05f));
    auto b = sim.AddClumps(tmpl, pts);
    sim.SetInitTimeStep(2e-5);
    sim.SetCDUpdateFreq(cdFreq);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.Initialize();
    sim.DoDynamics(0.1);
    auto tr = sim.Track(b);
    std::vector<float> out;
    for (size_t i = 0; i < pts.size(); i++) {
        const float3 p = tr->Pos(i), v = tr->Vel(i);
        const float4 q = tr->OriQ(i);
        out.insert(out.end(), {p.x, p.y, p.z, v.x, v.y, v.z, q.x, q.y, q.z, q.w});
    }
    return out;
}

}  // namespace

// Detection with a margin only adds pairs that are apart (they get zero force and fresh history),
// and each owner sums its contacts in a fixed order. So neither the detection frequency nor the
// thread count may change a single bit of the trajectory.
TEST(Determinism, TrajectoryIndependentOfDetectionFrequencyAndThreads) {
    const std::vector<float> ref = runPour(1, 2);
    ASSERT_GT(ref.size(), 1000u);
    EXPECT_EQ(runPour(30, 2), ref);
    EXPECT_EQ(runPour(10, 1), ref);
    EXPECT_EQ(runPour(1, 2), ref);
}
