// The CPU's force reduction: A's owner takes its loads in the force pass itself, B's owner in the
// reduction from its slots in the windows of the blocks of owners (backend/cpu/ForcePassLoop.h).
// Checked on a compressed block of three-sphere clumps between walls, with thousands of pairs so that
// the pass splits them among threads, blocks and chunks: every owner's sums obey Newton's third law
// and the balance of angular momentum (a pair's loads cancel, whatever owner takes them), and they
// are the same bit for bit for 1, 2 and 3 threads. Then the per-contact forces a storing pass keeps,
// in both of its forms, against each other and against the owners' sums.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "BackendFixture.h"
#include "api/ForceModelSetup.h"
#include "state/ContactTypeOf.h"
#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "backend/cpu/CpuForceModel.h"
#include "backend/cpu/ForcePassLoop.h"
#include "backend/cpu/Integration.h"
#include "backend/cpu/StandaloneContactSet.h"
#include "parallel/Parallel.h"
#include "runtime/ContactForceView.h"
#include "state/OwnerCentre.h"

using namespace deme;
using namespace deme_test;

namespace {

const float kRadius = 1e-3f;

// Three-sphere clumps on a grid closer than their size, turned differently, between two walls:
// most pairs overlap, and each clump's run of contacts as A mixes sphere and wall pairs.
Scene compressedBlock() {
    Scene scene;
    auto mat = std::make_shared<DEMMaterial>(
        std::map<std::string, double>{{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.05}}, 0);
    scene.materials.push_back(mat);
    scene.hasDomain = true;
    scene.domainLo = make_float3(-0.01f);
    scene.domainSize = make_float3(0.06f);
    auto walls = std::make_shared<DEMExternObj>();
    walls->AddPlane(make_float3(0, 0, 0.0005f), make_float3(0, 0, 1), mat);
    walls->AddPlane(make_float3(0.0005f, 0, 0), make_float3(1, 0, 0), mat);
    scene.externObjs.push_back(walls);
    auto t = std::make_shared<DEMClumpTemplate>();
    t->mass = 1e-5f;
    t->MOI = make_float3(1e-11f, 1.2e-11f, 1.4e-11f);
    t->radii = {kRadius, 0.8f * kRadius, 0.9f * kRadius};
    t->relPos = {make_float3(0.f), make_float3(1.2f * kRadius, 0, 0), make_float3(0, 1.1f * kRadius, 0)};
    t->materials = {mat, mat, mat};
    scene.templates.push_back(t);
    std::vector<float3> pos;
    std::vector<float4> q;
    const float gap = 2.1f * kRadius;
    for (int k = 0; k < 12; k++)
        for (int j = 0; j < 12; j++)
            for (int i = 0; i < 12; i++) {
                pos.push_back(make_float3(gap * (i + 0.5f), gap * (j + 0.5f), gap * (k + 0.5f)));
                const float a = 0.37f * (float)(i + 3 * j + 7 * k);
                q.push_back(make_float4(0.f, 0.f, std::sin(a), std::cos(a)));
            }
    auto batch =
        std::make_shared<DEMClumpBatch>(std::vector<std::shared_ptr<DEMClumpTemplate>>(pos.size(), t), pos);
    batch->SetOriQ(q);
    std::vector<float3> v;
    for (size_t n = 0; n < pos.size(); n++) v.push_back(make_float3(0.01f * (float)(n % 7), -0.02f * (float)(n % 5), 0.f));
    batch->SetVel(v);
    scene.batches.push_back(batch);
    return scene;
}

struct Loads {
    std::vector<float3> force, torque;
};

// The block's contact set, one force pass (the built-in Hertz-Mindlin model) and the reduction with
// `threads` threads; every owner's contact force and torque.
Loads passAndReduce(const Scene& scene, int threads, SimState* out = nullptr, ForceStore store = ForceStore::NONE,
                    double margin = 2e-4) {
    const int before = cpuThreadCount();
    setCpuThreadCount(threads);
    const ModelLayout layout =
        resolveModelLayout(DEMForceModel(DEMForceModel::Kind::FRICTIONAL_HERTZIAN), scene, "test");
    SimState s = assembleScene(scene, layout);
    s.owners.makeResults();  // the loads the reduction writes (as the CPU backend makes them)
    const CpuForceModel model = loadCpuForceModel(layout, "test");
    detectAndInstallContacts(s, margin);
    model.pass(s, 0.0, 1e-6, store);
    IntegrationSubset all;
    reduceContactForces(s, all);
    setCpuThreadCount(before);
    if (out) *out = s;
    return Loads{s.owners.contactForce, s.owners.contactTorque};
}

double3 toD(const float3& v) { return make_double3(v.x, v.y, v.z); }

}  // namespace

TEST(ForceReduction, OwnersSumsCancelAndDoNotDependOnTheThreadCount) {
    const Scene scene = compressedBlock();
    SimState s;
    const Loads one = passAndReduce(scene, 1, &s);
    // Large enough that the pass splits its contacts among threads and each thread's share among
    // several chunks (parallel/Parallel.h, backend/cpu/ForcePassLoop.h).
    ASSERT_GT(s.contacts.size(), 8 * PARALLEL_MIN_ITEMS);
    ASSERT_GT(s.owners.size(), 3 * FORCE_PASS_BLOCK_OWNERS);
    size_t wallPairs = 0;
    for (size_t i = 0; i < s.contacts.size(); i++) wallPairs += contactTypeAt(s, i) == SPHERE_ANALYTICAL;
    ASSERT_GT(wallPairs, 100u);

    // Newton's third law and the balance of angular momentum over all owners (the walls included):
    // every pair's force and moments cancel, so the sums are zero to the float rounding of the
    // loads (scale: the largest owner load times the number of contacts' rounding).
    double3 F = make_double3(0, 0, 0), L = make_double3(0, 0, 0);
    double fScale = 0.0, lScale = 0.0;
    for (size_t o = 0; o < s.owners.size(); o++) {
        const double3 f = toD(one.force[o]), x = ownerCentre(s, o);
        const double3 l = toD(one.torque[o]) + cross(x, f);
        F = F + f;
        L = L + l;
        fScale = std::max(fScale, length(f));
        lScale = std::max(lScale, length(l));
    }
    ASSERT_GT(fScale, 0.0);
    const double rounding = 1e-6 * std::sqrt((double)s.contacts.size());
    EXPECT_LT(length(F), rounding * fScale) << "sum of forces " << F.x << " " << F.y << " " << F.z;
    EXPECT_LT(length(L), rounding * lScale) << "sum of moments " << L.x << " " << L.y << " " << L.z;

    // The same sums, bit for bit, whatever the number of threads, and with the 4-byte slots a set
    // takes where a block's window has more slots than 2 bytes count.
    for (int threads : {2, 3, -2}) {
        const bool wide = threads < 0;
        const ScopedEnvironmentVariable width("DEME_WIDE_REDUCTION_SLOTS", wide ? "1" : "0");
        SimState used;
        const Loads many = passAndReduce(scene, std::abs(threads), &used);
        EXPECT_EQ(used.contacts.outSlotWide.empty(), !wide);
        EXPECT_EQ(used.contacts.outSlot.empty(), wide);
        ASSERT_EQ(many.force.size(), one.force.size());
        for (size_t o = 0; o < one.force.size(); o++) {
            ASSERT_EQ(std::memcmp(&many.force[o], &one.force[o], sizeof(float3)), 0) << "owner " << o;
            ASSERT_EQ(std::memcmp(&many.torque[o], &one.torque[o], sizeof(float3)), 0) << "owner " << o;
        }
    }
}

// A storing pass keeps every pair's force (a packed set: ContactArrays::force) or those of the pairs
// with one (ContactArrays::stored), which the readers' view spreads over the set: the two read the
// same, bit for bit, for any thread count; a pass that stores none leaves nothing to read. Summed
// onto the owners (+f on A, -f on B), the forces are the owners' contact forces (Newton's third law
// at every owner, to the float rounding of summing in another order).
TEST(ForceReduction, StoredForcesReadTheSameInBothFormsAndSumToTheOwnersForces) {
    const Scene scene = compressedBlock();
    SimState every, pairs, none;
    const Loads loads = passAndReduce(scene, 2, &every, ForceStore::EVERY_PAIR);
    passAndReduce(scene, 3, &pairs, ForceStore::PAIRS_WITH_FORCE);
    passAndReduce(scene, 2, &none, ForceStore::NONE);
    const size_t n = every.contacts.size();
    ASSERT_EQ(every.contacts.force.size(), n);
    EXPECT_EQ(every.contacts.stored.count(), 0u);
    EXPECT_TRUE(pairs.contacts.force.empty());
    EXPECT_TRUE(none.contacts.force.empty());
    EXPECT_EQ(none.contacts.stored.count(), 0u);
    const ContactForceView fe(every.contacts), fp(pairs.contacts), fn(none.contacts);
    size_t loaded = 0;
    std::vector<double3> sum(every.owners.size(), make_double3(0, 0, 0));
    double scale = 0.0;
    for (size_t i = 0; i < n; i++) {
        const float3 asEvery = fe[i], asPairs = fp[i];
        ASSERT_EQ(std::memcmp(&asEvery, &asPairs, sizeof(float3)), 0) << "contact " << i;
        EXPECT_EQ(fn[i].x, 0.f);
        const bool has = fe[i].x != 0.f || fe[i].y != 0.f || fe[i].z != 0.f;
        loaded += has;
        const double3 f = toD(fe[i]);
        const bodyID_t a = every.spheres.owner[every.contacts.geomA[i]], b = contactOwnerB(every, i);
        sum[a] = sum[a] + f;
        sum[b] = sum[b] - f;
        scale = std::max(scale, length(f));
    }
    EXPECT_EQ(pairs.contacts.stored.count(), loaded);
    ASSERT_GT(loaded, n / 4);  // half the pairs of the compressed block touch
    ASSERT_LT(loaded, n);      // and some within the margin do not
    for (size_t o = 0; o < sum.size(); o++)
        EXPECT_LT(length(sum[o] - toD(loads.force[o])), 1e-4 * scale) << "owner " << o;
}

// A set whose pairs are all apart (the margin reaches them, the spheres do not touch), as in a flow
// detected with a wide margin: a storing pass keeps nothing, and the set holds no load per pair (the
// windows hold one slot per B owner of a block, not one per pair).
TEST(ForceReduction, PairsApartKeepNoLoads) {
    const ScopedEnvironmentVariable narrow("DEME_WIDE_REDUCTION_SLOTS", "0");  // the 2-byte slots read below
    const Scene scene = compressedBlock();
    SimState s;
    // Three-sphere clumps 2.1 R apart: within 4 R of each other, so a margin of 5 R finds pairs
    // between spheres that do not touch; the ones that do are dropped by moving the clumps apart.
    Scene apart = scene;
    const std::vector<float3> pos = apart.batches[0]->GetPositions();
    std::vector<float3> spread;
    for (const float3& p : pos) spread.push_back(p * 2.5f + make_float3(2e-3f, 0.f, 2e-3f));  // off the walls
    apart.batches[0] = std::make_shared<DEMClumpBatch>(
        std::vector<std::shared_ptr<DEMClumpTemplate>>(pos.size(), scene.templates[0]), spread);
    apart.domainSize = make_float3(0.15f);
    passAndReduce(apart, 2, &s, ForceStore::PAIRS_WITH_FORCE, 5.0 * kRadius);
    const ContactArrays& c = s.contacts;
    ASSERT_GT(c.size(), s.owners.size());
    EXPECT_EQ(c.stored.count(), 0u);
    EXPECT_TRUE(c.force.empty());
    // Slots: one per (block, B owner outside the block), so fewer than the owners times the blocks
    // a B owner can be in; here about 0.75 per owner (1.5 while the block's own B owners had slots).
    EXPECT_LT(c.window.size(), s.owners.size());
    // A B owner in A's own block is summed in the pass (no slot), the others in their block's
    // window: each crossing contact's slot, in contact order, names its B owner there.
    ASSERT_TRUE(c.outSlotWide.empty());
    std::vector<std::vector<bodyID_t>> windowOwners(c.blockWindowStart.size() - 1);
    for (size_t o = 0; o < s.owners.size(); o++)
        for (uint32_t j = c.ownerBStart[o]; j < c.ownerBStart[o + 1]; j++) {
            const uint32_t w = c.ownerBSlots[j];
            const size_t k = std::upper_bound(c.blockWindowStart.begin(), c.blockWindowStart.end(), w) -
                             c.blockWindowStart.begin() - 1;
            windowOwners[k].resize(c.blockWindowStart[k + 1] - c.blockWindowStart[k]);
            windowOwners[k][w - c.blockWindowStart[k]] = (bodyID_t)o;
        }
    size_t inBlock = 0, crossing = 0;
    for (size_t i = 0; i < c.size(); i++) {
        const bodyID_t a = s.spheres.owner[c.geomA[i]], b = contactOwnerB(s, i);
        const bool same = a / FORCE_PASS_BLOCK_OWNERS == b / FORCE_PASS_BLOCK_OWNERS;
        inBlock += same;
        if (same) {
            EXPECT_TRUE(c.isBInItsBlock(b)) << "contact " << i;
            continue;
        }
        const size_t k = a / FORCE_PASS_BLOCK_OWNERS;
        ASSERT_LT(crossing, c.outSlot.size() - 1);
        ASSERT_GE(crossing, c.blockOutStart[k]);
        ASSERT_LT(crossing, c.blockOutStart[k + 1]);
        ASSERT_LT(c.outSlot[crossing], windowOwners[k].size()) << "contact " << i;
        EXPECT_EQ(windowOwners[k][c.outSlot[crossing]], b) << "contact " << i;
        crossing++;
    }
    ASSERT_GT(inBlock, 0u);
    ASSERT_LT(inBlock, c.size());
    EXPECT_EQ(crossing + 1, c.outSlot.size());  // two bytes a crossing contact, and one entry past
    std::cout << "[ windows  ] " << (double)c.window.size() / (double)s.owners.size() << " slots per owner, "
              << (double)c.size() / (double)s.owners.size() << " pairs per owner" << std::endl;
    for (size_t o = 0; o < s.owners.size(); o++) {
        EXPECT_EQ(s.owners.contactForce[o].x, 0.f);
        EXPECT_EQ(s.owners.contactForce[o].z, 0.f);
    }
}
