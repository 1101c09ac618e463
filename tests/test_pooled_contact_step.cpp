// The GPU's pooled contact history (state/HistoryPool.h, dynamics/PooledContactStep.h) checked
// without a GPU: the per-pair step the pooled force pass runs, called here on the host over a view
// of a CPU state, against the step over W floats per pair (the dense form) that both backends run.
// Pass after pass (time advancing, the spheres' radii changing so that pairs begin and stop touching), every pair's
// load is the same to the bit, and the pool read back per pair (state/HistoryPoolExpand.h) is the dense history, to the
// bit; a pool too small for the pairs that take a history leaves them without a slot, and growing it and filling
// those pairs (what CudaDynamics::finishPausedStep runs) gives the same histories and forces. Some pairs are ranked
// (their slots given at an installation), the others take late slots (tests/HostHistoryPool.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "BackendFixture.h"
#include "HostHistoryPool.h"
#include "api/ForceModelSetup.h"
#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "backend/cpu/HistoryForm.h"
#include "backend/cpu/StandaloneContactSet.h"
#include "dynamics/PooledContactStep.h"
#include "physics/BuiltInForceModels.h"
#include "state/HistoryPoolExpand.h"
#include "state/StateView.h"
#include "state/StateViewScalars.h"

using namespace deme;

namespace {

// Spheres of radius 1 mm on a grid closer than their size above a floor, moving: most pairs of the
// set overlap, some are apart within the margin, and the tangential history grows pass by pass.
Scene overlappingGrid() {
    const float r = 1e-3f;
    Scene scene;
    auto mat = std::make_shared<DEMMaterial>(
        std::map<std::string, double>{{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.05}}, 0);
    scene.materials.push_back(mat);
    scene.hasDomain = true;
    scene.domainLo = make_float3(-0.01f);
    scene.domainSize = make_float3(0.04f);
    auto walls = std::make_shared<DEMExternObj>();
    walls->AddPlane(make_float3(0, 0, 0.0008f), make_float3(0, 0, 1), mat);
    scene.externObjs.push_back(walls);
    auto t = std::make_shared<DEMClumpTemplate>();
    t->mass = 1e-5f;
    t->MOI = make_float3(1e-11f);
    t->radii = {r};
    t->relPos = {make_float3(0.f)};
    t->materials = {mat};
    scene.templates.push_back(t);
    std::vector<float3> pos, vel;
    // Rows 1.96 r apart along x (touching), 2.3 r apart along y (apart, within the margin).
    for (int k = 0; k < 4; k++)
        for (int j = 0; j < 6; j++)
            for (int i = 0; i < 6; i++) {
                pos.push_back(make_float3(1.96f * r * (float)i, 2.3f * r * (float)j, 1.97f * r * (float)k + r));
                const float n = (float)pos.size();
                vel.push_back(
                    make_float3(0.01f * std::sin(n), 0.02f * std::cos(1.7f * n), -0.01f * std::sin(0.3f * n)));
            }
    auto batch = std::make_shared<DEMClumpBatch>(std::vector<std::shared_ptr<DEMClumpTemplate>>(pos.size(), t), pos);
    batch->SetVel(vel);
    batch->SetAngVel(std::vector<float3>(pos.size(), make_float3(3.f, -2.f, 1.f)));
    scene.batches.push_back(batch);
    return scene;
}

// A view of the host state, as the GPU's of device memory.
struct HostPointer {
    template <class T, class A>
    void operator()(T*& v, A& a, FieldRole) const {
        v = a.empty() ? nullptr : a.data();
    }
};

StateView hostView(SimState& s) {
    StateView v{};
    const HostPointer p;
    forEachOwnerField(v.owners, s.owners, p);
    forEachMassField(v.massProps, s.massProps, p);
    forEachSphereField(v.spheres, s.spheres, p);
    forEachAnalyticalField(v.analytical, s.analytical, p);
    forEachTriangleField(v.triangles, s.triangles, p);
    forEachContactField(v.contacts, s.contacts, p);
    v.pairAs = wholePairAs(s.contacts.geomA.data());  // (the device's are compact: CompactPairA.*)
    forEachCacheField(v.cache, s.cache, p);
    forEachScratchField(v.integrationScratch, s.integrationScratch, p);
    setViewScalars(v, s);
    v.numContacts = (uint32_t)s.contacts.size();
    return v;
}

bool sameBits(const float3& a, const float3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST(PooledContactStep, SameLoadsAndHistoriesAsTheDenseFormThroughPausesAndFills) {
    const deme_test::ScopedEnvironmentVariable dense("DEME_CONTACT_HISTORY", "dense");
    const Scene scene = overlappingGrid();
    const ModelLayout layout =
        resolveModelLayout(DEMForceModel(DEMForceModel::Kind::FRICTIONAL_HERTZIAN), scene, "test");
    SimState s = assembleScene(scene, layout);
    detectAndInstallContacts(s, 0.6e-3);
    s.contacts.restoreA();
    densifyHistory(s);
    const size_t n = s.contacts.size();
    constexpr unsigned int W = FrictionalHertzModel::kNumContactWildcards;
    ASSERT_EQ(s.numWildcards, W);
    ASSERT_EQ(s.contacts.wildcards.size(), n * W);
    const MaterialTables& mt = s.materials;
    const FrictionalHertzModel model{PairTable{mt.mu.data(), mt.count}, PairTable{mt.Crr.data(), mt.count},
                                     PairTable{mt.E_eff.data(), mt.count}, PairTable{mt.G_eff.data(), mt.count},
                                     PairTable{mt.beta_CoR.data(), mt.count}};
    std::vector<float3> denseForce(n);
    StateView dv = hostView(s);
    dv.contacts.force = denseForce.data();
    // The pooled state: the same arrays, but history and forces in the pool (which starts empty,
    // so that the first pass leaves every pair that takes a history pending).
    std::vector<float> denseHistory = s.contacts.wildcards;
    StateView pv = hostView(s);
    pv.contacts.wildcards = nullptr;
    // Every fifth pair ranked (a slot from the installation, its history zeros), the others late
    // once they take a history.
    std::vector<bool> ranked(n);
    for (size_t i = 0; i < n; i++) ranked[i] = i % 5 == 0;
    deme_test::HostHistoryPool hp(n, ranked, W);
    std::fill(hp.pool.begin(), hp.pool.end(), 0.f);
    const uint32_t rankedSlots = hp.rankedSlots;
    ASSERT_GT(rankedSlots, 10u);
    const auto into = [&](StateView& v) {
        v.historyPool = hp.view();
        v.contacts.force = hp.force.data();
    };
    dv.contacts.wildcards = denseHistory.data();

    size_t touching = 0, apart = 0, pauses = 0, claimedWithRoom = 0;
    const float dt = 1e-6f;
    // The spheres grow and shrink between passes, so that pairs begin and stop touching: some
    // claim a slot where the pool has room, some where it has none, some give their history up.
    const std::vector<float> radius0 = s.spheres.radius;
    const float scale[] = {1.f, 1.f, 1.1f, 1.2f, 0.95f, 1.25f, 1.3f, 1.f};
    for (int pass = 0; pass < 8; pass++) {
        SCOPED_TRACE(pass);
        const float time = (float)pass * dt;
        for (size_t k = 0; k < radius0.size(); k++) s.spheres.radius[k] = scale[pass] * radius0[k];
        const uint32_t usedBefore = hp.control.used, capacityBefore = hp.capacity;
        into(pv);
        std::vector<ContactLoad> dl(n), pl(n);
        std::vector<bool> da(n), pa(n);
        for (size_t i = 0; i < n; i++) {
            bool applied = false;
            const ContactIds ids = contactIds<ANY_CONTACT_TYPE>(dv, i);
            const bool t =
                contactStepOfType<FrictionalHertzModel, ANY_CONTACT_TYPE>(dv, model, i, ids, time, dt, applied, dl[i]);
            denseForce[i] = applied ? dl[i].force : make_float3(0.f);
            da[i] = applied;
            if (pass == 0) (t ? touching : apart)++;
            bool pApplied = false;
            pooledContactStep<FrictionalHertzModel, ANY_CONTACT_TYPE>(pv, model, i, ids, time, dt, pApplied, pl[i]);
            pa[i] = pApplied;
        }
        for (size_t i = 0; i < n; i++) {
            ASSERT_EQ(da[i], pa[i]) << "pair " << i;
            if (!da[i]) continue;
            ASSERT_TRUE(sameBits(dl[i].force, pl[i].force)) << "pair " << i;
            ASSERT_TRUE(sameBits(dl[i].torqueA, pl[i].torqueA)) << "pair " << i;
            ASSERT_TRUE(sameBits(dl[i].torqueB, pl[i].torqueB)) << "pair " << i;
        }
        if (hp.control.used > usedBefore && usedBefore < capacityBefore) claimedWithRoom++;
        if (hp.control.paused) {
            // What finishPausedStep does: room for every claim, the counter set back to the old
            // capacity, then the pairs left without a slot again.
            pauses++;
            ASSERT_GT(hp.control.used, hp.capacity);
            const uint32_t kept = hp.capacity, claims = hp.control.used;
            hp.grow(hp.control.used + (pass % 2 ? 0u : 40u));
            hp.control.used = kept;
            hp.control.paused = 0;
            hp.control.filling = 1;
            into(pv);
            for (size_t i = 0; i < n; i++)
                fillPendingHistory<FrictionalHertzModel, ANY_CONTACT_TYPE>(
                    pv, model, i, contactIds<ANY_CONTACT_TYPE>(pv, i), time, dt);
            hp.control.filling = 0;
            ASSERT_EQ(hp.control.paused, 0u);
            ASSERT_EQ(hp.control.used, claims);  // the fill claims exactly what the pass could not keep
        }
        ASSERT_EQ(hp.control.lost, 0u);
        const std::vector<uint32_t> slot = hp.slots(n);
        for (size_t i = 0; i < n; i++) {
            ASSERT_TRUE(slot[i] == NO_HISTORY_SLOT || slot[i] < hp.capacity);
            if (ranked[i]) ASSERT_LT(slot[i], rankedSlots) << "pair " << i;  // a ranked pair keeps its rank
        }
        std::vector<float> expanded(n * W);
        expandPooledHistory(slot.data(), n, hp.pool.data(), W, expanded.data());
        ASSERT_EQ(0, std::memcmp(expanded.data(), denseHistory.data(), expanded.size() * sizeof(float)));
        std::vector<float3> forces(n);
        expandPooledForces(slot.data(), n, hp.force.data(), forces.data());
        for (size_t i = 0; i < n; i++) ASSERT_TRUE(sameBits(forces[i], denseForce[i])) << "pair " << i;
        // Every claimed slot is a pair's, each once (a pair keeps its slot once its history has ended).
        std::vector<uint32_t> taken;
        for (uint32_t k : slot)
            if (k != NO_HISTORY_SLOT) taken.push_back(k);
        std::sort(taken.begin(), taken.end());
        EXPECT_TRUE(std::adjacent_find(taken.begin(), taken.end()) == taken.end());
        EXPECT_EQ(taken.size(), (size_t)hp.control.used);
    }
    // The scene has both kinds of pairs, and the empty pool paused the first pass.
    EXPECT_GT(touching, 50u);
    EXPECT_GT(apart, 50u);
    EXPECT_GE(pauses, 2u);
    EXPECT_GE(claimedWithRoom, 1u);
}
