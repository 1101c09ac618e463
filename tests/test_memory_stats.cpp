// Memory by array group (DEMSolver::GetMemoryStats, ShowMemoryStats; docs/memory.md): each group
// holds at least the arrays the state's field lists give it (state/StateFields.h, one value per item
// and field), the groups add up to the totals, and on the GPU to the bytes the device buffers hold.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "BackendFixture.h"
#include "TestHelpers.h"
#include "state/StateFields.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(MemoryStatsGroups);

namespace {

// The bytes one item takes in a field group: the sizes of its fields' types.
template <class T>
struct FieldBytes {
    size_t bytes = sizeof(T);
};
struct SumBytes {
    size_t& sum;
    bool results = true;  // false: only the RESULT fields
    template <class F>
    void operator()(const F& f, const F&, FieldRole role) const {
        if (role != FieldRole::HOST && (results || role == FieldRole::RESULT)) sum += f.bytes;
    }
};
size_t ownerBytes() {
    size_t sum = 0;
    OwnerFields<FieldBytes> f;
    forEachOwnerField(f, f, SumBytes{sum});
    return sum;
}
// An owner's results (the last step's loads, its travel: state/SimState.h).
size_t ownerResultBytes() {
    size_t sum = 0;
    OwnerFields<FieldBytes> f;
    forEachOwnerField(f, f, SumBytes{sum, false});
    return sum;
}
// A sphere's bytes in the geometry group where, as in the scene below, every clump is one sphere at
// its centre (state/SphereLayout.h): its fields but its offset in the owner's frame and its owner's
// index (sphere i is owner i's), and no cached centre or arm (its owner's position is decoded where
// read, state/OwnerCentre.h).
size_t sphereBytes() {
    size_t sum = 0;
    SphereFields<FieldBytes> f;
    forEachSphereField(f, f, SumBytes{sum});
    return sum - sizeof(float3) - sizeof(bodyID_t);
}

}  // namespace

// 1,000 spheres settling in a box: every group the run uses holds at least its arrays' bytes per
// item, the totals are the groups' sums, and on the GPU the groups' sum is what the device buffers
// hold (GetDeviceMemUsage).
DEME_BACKEND_TEST(MemoryStatsGroups, GroupsHoldTheirArraysAndAddUp) {
    DEMSolver sim;
    addThousandSphereBed(sim);
    EXPECT_NE(demeErrorMessage([&] { sim.GetMemoryStats(); }).find("GetMemoryStats"), std::string::npos);
    sim.Initialize();
    sim.DoDynamics(0.3);
    const size_t n = 1000, contacts = sim.GetNumContacts();
    ASSERT_GT(contacts, n / 2);  // settled into a bed
    const MemoryStats m = sim.GetMemoryStats();
    EXPECT_EQ(m.spheres, n);

    // The host state (both backends keep it): owners (a GPU run's without their results, below),
    // spheres, contact pairs; detection's scratch.
    EXPECT_GE(m.host(MemoryGroup::OWNER_STATE), n * (ownerBytes() - (onGpu() ? ownerResultBytes() : 0)));
    EXPECT_GE(m.host(MemoryGroup::GEOMETRY), n * sphereBytes());
    EXPECT_EQ(m.host(MemoryGroup::WILDCARDS), 0u);  // the default model has no owner or geometry wildcards
    size_t hostSum = 0;
    for (size_t b : m.hostBytes) hostSum += b;
    EXPECT_EQ(m.hostTotal(), hostSum);

    size_t deviceSum = 0;
    for (size_t b : m.deviceBytes) deviceSum += b;
    EXPECT_EQ(m.deviceTotal(), deviceSum);
    // The owners' results: the CPU's steps write them in the host state; a GPU run's host fetches
    // them for a checkpoint (every owner's: 1,000 spheres and the box's) and lets them go
    // when the steps go on.
    const size_t ownersBefore = m.host(MemoryGroup::OWNER_STATE);
    sim.WriteCheckpoint((scratchDir() / "memory.ckpt").string());
    const size_t fetched = sim.GetMemoryStats().host(MemoryGroup::OWNER_STATE) - ownersBefore;
    if (onGpu()) {
        EXPECT_GE(fetched, n * ownerResultBytes());
        EXPECT_LE(fetched, (n + 8) * ownerResultBytes());
        sim.DoDynamics(1e-4);
        EXPECT_EQ(sim.GetMemoryStats().host(MemoryGroup::OWNER_STATE), ownersBefore);
    } else {
        EXPECT_EQ(fetched, 0u);
    }
    if (!onGpu()) {
        // The CPU steps on the host arrays: the contact set and the detector's bins (kept between
        // detections in so small a scene) are there. Pairs, type and Hertz-Mindlin's tangential
        // history (3 floats) per contact.
        EXPECT_GE(m.host(MemoryGroup::CONTACTS), contacts * (2 * sizeof(bodyID_t) + 1 + 3 * sizeof(float)));
        EXPECT_GT(m.host(MemoryGroup::DETECTION), n * sizeof(uint32_t));
        EXPECT_EQ(m.deviceTotal(), 0u);
        EXPECT_EQ(m.devicePeakTotal(), 0u);
        return;
    }
    // The groups at the device's peak add up to the process's peak (the "at most" of the run
    // summary), which is at least what the run holds now. (The process's: in a test binary an
    // earlier test may have made it, so no group is required to hold something there.)
    EXPECT_GE(m.devicePeakTotal(), m.deviceTotal());
    EXPECT_LE(m.devicePeakTotal(), sim.GetRunSummary().deviceBytesPeak);  // the peak only rises
    // The GPU: the device copy of the state, two contact sets, kT's bins and snapshot. The contact
    // set stays there: the host copies it only for a call that reads it (here a contact file) and
    // lets the copy go when the steps go on.
    EXPECT_EQ(m.host(MemoryGroup::CONTACTS), 0u);
    sim.WriteContactFile((scratchDir() / "contacts.csv").string());
    EXPECT_GE(sim.GetMemoryStats().host(MemoryGroup::CONTACTS), contacts * (2 * sizeof(bodyID_t) + 1));
    sim.DoDynamics(1e-4);
    EXPECT_EQ(sim.GetMemoryStats().host(MemoryGroup::CONTACTS), 0u);
    EXPECT_EQ(m.deviceTotal(), sim.GetDeviceMemUsage());  // this test's solver is the only one
    EXPECT_GE(m.device(MemoryGroup::OWNER_STATE), n * ownerBytes());
    EXPECT_GE(m.device(MemoryGroup::GEOMETRY), n * sphereBytes());
    EXPECT_GE(m.device(MemoryGroup::CONTACTS), contacts * (2 * sizeof(bodyID_t) + 1 + 3 * sizeof(float)));
    EXPECT_GT(m.device(MemoryGroup::DETECTION), n * sizeof(uint32_t));
    EXPECT_EQ(m.device(MemoryGroup::WILDCARDS), 0u);
}

// The printed table names every group and the total, with bytes per sphere.
TEST(MemoryStatsReport, ShowMemoryStatsPrintsEveryGroup) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    sim.SetBackend("cpu");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.4));
    sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.1f);
    auto type = sim.LoadSphereType((float)sphereMass(0.005, 2500), 0.005f, mat);
    sim.AddClumps(type, {make_float3(0, 0, 0), make_float3(0.02f, 0, 0)});
    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    testing::internal::CaptureStdout();
    sim.ShowMemoryStats();
    const std::string out = testing::internal::GetCapturedStdout();
    for (int g = 0; g < NUM_MEMORY_GROUPS; g++)
        EXPECT_NE(out.find(memoryGroupName((MemoryGroup)g)), std::string::npos) << memoryGroupName((MemoryGroup)g);
    EXPECT_NE(out.find("total"), std::string::npos);
    EXPECT_NE(out.find("2 spheres"), std::string::npos);
}
