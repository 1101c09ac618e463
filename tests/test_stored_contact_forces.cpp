// Per-contact forces as a call leaves them (docs/memory.md): the force each contact exerted in the
// call's last step. The GPU keeps them in the memory of the idle contact set's history between two
// detections (backend/cuda/CudaContactSets.cpp), so these tests run calls that install new sets in
// their middle and read the forces after each.
//
// The check is Newton's third law at every owner: the forces the contact file gives, summed onto the
// owners (+f on A, -f on B), are the contact force the same step added to each owner, which a
// tracker reads (DEMTracker::ContactForces, the owners' loads). Both come from one force pass, summed
// in different orders in float: they agree to 1e-4 of the largest contact force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(StoredContactForces);

namespace {

struct ContactRow {
    int ownerA, ownerB;
    double fx, fy, fz;
};

// The contact file's rows (its header names the columns).
std::vector<ContactRow> readContactFile(const std::string& path) {
    std::ifstream f(path);
    std::string line;
    std::getline(f, line);
    std::vector<std::string> header;
    {
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) header.push_back(cell);
    }
    auto column = [&](const char* name) {
        const auto it = std::find(header.begin(), header.end(), name);
        EXPECT_NE(it, header.end()) << name;
        return (size_t)(it - header.begin());
    };
    const size_t cA = column("ownerA"), cB = column("ownerB"), cx = column("f_x"), cy = column("f_y"),
                 cz = column("f_z");
    std::vector<ContactRow> rows;
    while (std::getline(f, line)) {
        std::vector<std::string> cells;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) cells.push_back(cell);
        rows.push_back({std::stoi(cells[cA]), std::stoi(cells[cB]), std::stod(cells[cx]), std::stod(cells[cy]),
                        std::stod(cells[cz])});
    }
    return rows;
}

// 1,000 spheres fallen into a bed, still settling: five calls of 500 steps, with a contact set at
// most every 20 steps (asynchronous detection on the GPU: sets installed in the calls' middle), and
// after each call the contact file's forces summed onto the spheres equal their contact forces.
void expectForcesOfTheLastStep(const std::string& dir, bool frictionless) {
    DEMSolver sim;
    auto grains = addThousandSphereBed(sim, 0.0007f);  // disordered: its contacts push sideways too
    auto tracker = sim.Track(grains);
    if (frictionless) sim.UseFrictionlessHertzianModel();
    sim.SetCDUpdateFreq(20);
    sim.SetCDMaxUpdateFreq(20);
    sim.Initialize();
    sim.DoDynamics(0.05);  // into a bed
    const size_t n = tracker->GetNumOwners();
    size_t checkedContacts = 0;
    for (int call = 0; call < 5; call++) {
        sim.DoDynamics(500 * 2e-5);
        const std::string file = dir + "/contacts" + std::to_string(call) + ".csv";
        sim.WriteContactFile(file);
        sim.FlushOutput();
        const std::vector<ContactRow> rows = readContactFile(file);
        std::vector<double> sum(3 * n, 0.0);
        double largest = 0.0;
        for (const ContactRow& c : rows) {
            ASSERT_GE(c.ownerA, 0);
            ASSERT_LT((size_t)c.ownerA, n);  // every contact has a sphere as A
            sum[3 * c.ownerA] += c.fx, sum[3 * c.ownerA + 1] += c.fy, sum[3 * c.ownerA + 2] += c.fz;
            if (c.ownerB >= 0 && (size_t)c.ownerB < n)
                sum[3 * c.ownerB] -= c.fx, sum[3 * c.ownerB + 1] -= c.fy, sum[3 * c.ownerB + 2] -= c.fz;
            largest = std::max(largest, std::sqrt(c.fx * c.fx + c.fy * c.fy + c.fz * c.fz));
        }
        ASSERT_GT(largest, 0.0) << "call " << call;
        const std::vector<float3> loads = tracker->ContactForces();
        ASSERT_EQ(loads.size(), n);
        for (size_t o = 0; o < n; o++) {
            EXPECT_NEAR(sum[3 * o], loads[o].x, 1e-4 * largest) << "call " << call << ", owner " << o;
            EXPECT_NEAR(sum[3 * o + 1], loads[o].y, 1e-4 * largest) << "call " << call << ", owner " << o;
            EXPECT_NEAR(sum[3 * o + 2], loads[o].z, 1e-4 * largest) << "call " << call << ", owner " << o;
        }
        checkedContacts += rows.size();
    }
    EXPECT_GT(checkedContacts, 1000u);  // the bed's contacts, not a handful
}

}  // namespace

// Hertz-Mindlin keeps four wildcards a pair: the forces fit the idle set's history memory.
DEME_BACKEND_TEST(StoredContactForces, EveryCallLeavesTheForcesOfItsLastStep) {
    expectForcesOfTheLastStep(scratchDir().string(), false);
}

// The frictionless model keeps none: the lent memory grows to hold the forces, and the history
// mapping of the next set takes it back all the same.
DEME_BACKEND_TEST(StoredContactForces, AModelWithoutHistoryStoresThemToo) {
    expectForcesOfTheLastStep(scratchDir().string(), true);
}
