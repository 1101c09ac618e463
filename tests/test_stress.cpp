// The stress of the grains (CreateInspector("stress", lo, hi), include/deme/Stress.h): the contact
// part of a pressed pair is F l / V; the kinetic part of a gas is its velocity covariance; and in a
// settled bed periodic in x and y (no side walls, so no Janssen effect) the floor carries the whole
// weight and the vertical stress at a depth is the weight of the grains above it per unit area.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <random>
#include <vector>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(Stress);

TEST(StressInspector, BadInputIsAnError) {
    DEMSolver sim;
    EXPECT_NE(demeErrorMessage([&] { sim.CreateInspector("stress"); }).find("takes a region"), std::string::npos);
    EXPECT_NE(demeErrorMessage([&] { sim.CreateInspector("clump_mass", make_float3(0), make_float3(1)); })
                  .find("takes no region"),
              std::string::npos);
    EXPECT_NE(demeErrorMessage([&] { sim.CreateInspector("stress", make_float3(0), make_float3(1, 0, 1)); })
                  .find("hi > lo"),
              std::string::npos);
    EXPECT_NE(demeErrorMessage([&] { sim.CreateInspector("clump_mass")->GetStress(); }).find("not a stress"),
              std::string::npos);
}

// Two spheres pressed together along x, at rest, no gravity: after one step the region around both
// has sigma_xx = F l / V (F the contact force, l the distance between the centres) and nothing
// else (to 1e-6 of it); a region around one of them only, F a / V with a its arm to the contact point;
// their kinetic part is F dt / m small (under 1e-5 of the contact part).
DEME_BACKEND_TEST(Stress, PressedPairGivesForceTimesDistanceOverVolume) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.4));
    sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.2f);
    const double r = 0.008, l = 0.0156;  // overlap 0.4 mm
    auto type = sim.LoadSphereType((float)sphereMass(r, 2500), (float)r, mat);
    auto pair = sim.AddClumps(type, {make_float3((float)(-l / 2), 0, 0), make_float3((float)(l / 2), 0, 0)});
    sim.SetInitTimeStep(1e-6);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.Initialize();
    auto tr = sim.Track(pair);
    auto both = sim.CreateInspector("stress", make_float3(-0.05f), make_float3(0.05f));
    auto left = sim.CreateInspector("stress", make_float3(-0.05f), make_float3(0.f, 0.05f, 0.05f));
    sim.DoStepDynamics();
    const double F = -tr->ContactForce(0).x;  // A is pushed towards -x
    ASSERT_GT(F, 0.1);
    const double dist = (double)(tr->Pos(1).x - tr->Pos(0).x);
    const StressTensor s = both->GetStress();
    const double V = s.volume;  // of the region given in floats
    EXPECT_EQ(s.grains, 2u);
    EXPECT_NEAR(V, 1e-3, 1e-9);
    EXPECT_NEAR(s.contact[0], F * dist / V, 1e-6 * F * dist / V);
    for (int k = 1; k < 9; k++) EXPECT_NEAR(s.contact[k], 0.0, 1e-6 * F * dist / V) << k;
    EXPECT_LT(std::fabs(s.kinetic[0]), 1e-5 * s.contact[0]);
    EXPECT_NEAR(both->GetValue(), s.total[0] / 3.0, 1e-9 * s.total[0]);
    // One side: A's arm reaches from its centre to the middle of the overlap.
    const StressTensor a = left->GetStress();
    EXPECT_EQ(a.grains, 1u);
    EXPECT_NEAR(a.contact[0], F * (dist / 2) / a.volume, 1e-5 * F * dist / V);
}

// A dilute gas with no contacts in a fully periodic box: the kinetic part is (1/V) sum m u u with u
// the velocities less their mean, computed here from the tracker's velocities (to 1e-6).
DEME_BACKEND_TEST(Stress, GasKineticPartIsTheVelocityCovariance) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 1.0, 0.0));
    sim.InstructBoxDomainDimension({0.f, 0.2f}, {0.f, 0.2f}, {0.f, 0.2f});
    sim.InstructBoxDomainPeriodicity("xyz");
    const double r = 0.002, m = sphereMass(r, 2500);
    auto type = sim.LoadSphereType((float)m, (float)r, mat);
    std::vector<float3> pts;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            for (int k = 0; k < 4; k++) pts.push_back(make_float3(0.025f + 0.05f * i, 0.025f + 0.05f * j, 0.025f + 0.05f * k));
    auto gas = sim.AddClumps(type, pts);
    sim.SetInitTimeStep(1e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.Initialize();
    auto tr = sim.Track(gas);
    std::mt19937 rng(5);
    std::normal_distribution<float> g(0.f, 0.5f);
    for (size_t k = 0; k < pts.size(); k++) tr->SetVel(make_float3(g(rng) + 0.3f, g(rng), g(rng) - 0.1f), k);
    sim.DoDynamics(100 * 1e-5);
    auto inspector = sim.CreateInspector("stress", make_float3(0.f), make_float3(0.2f));
    const StressTensor s = inspector->GetStress();
    EXPECT_EQ(s.grains, pts.size());
    EXPECT_EQ(s.contacts, 0u);
    double mean[3] = {0, 0, 0};
    std::vector<float3> v = tr->Velocities();
    for (const float3& u : v) {
        mean[0] += u.x / v.size();
        mean[1] += u.y / v.size();
        mean[2] += u.z / v.size();
    }
    double expected[9] = {};
    for (const float3& u : v) {
        const double d[3] = {u.x - mean[0], u.y - mean[1], u.z - mean[2]};
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) expected[3 * i + j] += (double)(float)m * d[i] * d[j] / (0.2 * 0.2 * 0.2);
    }
    for (int k = 0; k < 9; k++) EXPECT_NEAR(s.kinetic[k], expected[k], 1e-6 * expected[0]) << k;
    for (int k = 0; k < 9; k++) EXPECT_EQ(s.contact[k], 0.0) << k;
}

// About 1,000 spheres settle on a floor in a box periodic in x and y (no side walls, so the walls
// carry nothing and there is no Janssen effect). The floor's force equals the weight (0.5 %; it was
// 0.001 %), and sigma_zz of a slab four diameters thick at mid-depth equals the weight above per
// unit area, averaged over the slab (3 %, the bound; it was 0.5 %: each grain weighs on the
// planes below its centre).
DEME_BACKEND_TEST(Stress, SettledPeriodicBedCarriesItsWeight) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.5, 0.02));
    const float L = 0.04f, r = 0.002f;
    sim.InstructBoxDomainDimension({0.f, L}, {0.f, L}, {0.f, 0.08f});
    sim.InstructBoxDomainPeriodicity("xy");
    auto floor = sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    const double m = sphereMass(r, 2500), g = 9.81;
    auto type = sim.LoadSphereType((float)m, r, mat);
    // A lattice that keeps 2.02 r from its images across the faces.
    auto pts = HCPSampler(2.02f * r).SampleBox(make_float3(L / 2, L / 2, 0.02f),
                                              make_float3(L / 2 - 1.01f * r, L / 2 - 1.01f * r, 0.0185f));
    auto bed = sim.AddClumps(type, pts);
    sim.SetInitTimeStep(2e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, (float)-g));
    sim.Initialize();
    sim.DoDynamics(0.6);
    auto speed = sim.CreateInspector("clump_max_absv");
    ASSERT_LT(speed->GetValue(), 0.01);
    const double n = (double)pts.size(), weight = n * (double)(float)m * g;
    ASSERT_GT(n, 800);
    auto floorTracker = sim.Track(floor);
    EXPECT_NEAR(-floorTracker->ContactForce().z, weight, 0.005 * weight);  // the grains press it down

    // The slab: four diameters around mid-depth (two gave 2.2 %, the slab's edges cutting grains).
    auto tr = sim.Track(bed);
    const std::vector<float3> p = tr->Positions();
    double top = 0.0;
    for (const float3& x : p) top = std::max(top, (double)x.z);
    const double zc = 0.5 * top, H = 8.0 * r, lo = zc - H / 2, hi = zc + H / 2;
    auto slab = sim.CreateInspector("stress", make_float3(0.f, 0.f, (float)lo), make_float3(L, L, (float)hi));
    const StressTensor s = slab->GetStress();
    // The plane at height z carries the grains whose centres lie above it; averaged over the slab.
    double expected = 0.0;
    for (const float3& x : p) expected += (double)(float)m * g * std::clamp(((double)x.z - lo) / H, 0.0, 1.0);
    expected /= (double)L * L;
    EXPECT_GT(s.grains, 50u);
    EXPECT_NEAR(s.total[8], expected, 0.03 * expected);
}

// The stress field (WriteStressField): one row per cell, x fastest, each cell's centre; the cells'
// contact stresses, weighted by their volumes, add up to the whole box's (to 1e-9), and every grain
// is in one cell; the file is written as CSV or VTU like the sphere files, and joins a series.
DEME_BACKEND_TEST(Stress, FieldCellsAddUpToTheWholeBox) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.5, 0.02));
    sim.InstructBoxDomainDimension({0.f, 0.04f}, {0.f, 0.04f}, {0.f, 0.06f});
    sim.InstructBoxDomainPeriodicity("xy");
    sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    const float r = 0.002f;
    auto pts = HCPSampler(2.02f * r).SampleBox(make_float3(0.02f, 0.02f, 0.012f),
                                              make_float3(0.02f - 1.01f * r, 0.02f - 1.01f * r, 0.01f));
    sim.AddClumps(sim.LoadSphereType((float)sphereMass(r, 2500), r, mat), pts);
    sim.SetInitTimeStep(2e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.Initialize();
    sim.DoDynamics(0.05);
    const float3 lo = make_float3(0.f), hi = make_float3(0.04f, 0.04f, 0.03f);
    const StressTensor whole = sim.CreateInspector("stress", lo, hi)->GetStress();
    const std::string csv = (scratchDir() / "stress.csv").string();
    sim.WriteStressField(csv, lo, hi, 2, 3, 4);
    sim.FlushOutput();
    std::ifstream f(csv);
    std::string header, line;
    std::getline(f, header);
    EXPECT_EQ(header.substr(0, 12), "X,Y,Z,sxx,sx");
    std::vector<std::vector<double>> rows;
    while (std::getline(f, line)) {
        std::vector<double> v;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
        rows.push_back(v);
    }
    ASSERT_EQ(rows.size(), 24u);
    // Columns: X, Y, Z, 9 total, 9 contact, 9 kinetic, pressure, grains.
    ASSERT_EQ(rows[0].size(), 3u + 27u + 2u);
    EXPECT_NEAR(rows[0][0], 0.01, 1e-6);
    EXPECT_NEAR(rows[1][0], 0.03, 1e-6);  // x fastest
    EXPECT_NEAR(rows[2][1], 0.04 / 3 * 1.5, 1e-6);
    double szz = 0.0, grains = 0.0;
    for (const auto& row : rows) {
        szz += row[3 + 9 + 8] / 24.0;  // contact zz, each cell 1/24 of the box
        grains += row[3 + 27 + 1];
    }
    EXPECT_NEAR(szz, whole.contact[8], 1e-9 * std::fabs(whole.contact[8]));
    EXPECT_EQ((size_t)grains, whole.grains);
    EXPECT_GT(whole.contact[8], 0.0);
    sim.SetOutputFormat("VTU");
    const std::string pvd = (scratchDir() / "stress.pvd").string();
    sim.SetOutputSeries("stress", pvd);
    sim.WriteStressField((scratchDir() / "stress.vtu").string(), lo, hi, 2, 3, 4);
    sim.FlushOutput();
    EXPECT_TRUE(std::filesystem::exists((scratchDir() / "stress.vtu").string()));
    std::ifstream series(pvd);
    const std::string listing((std::istreambuf_iterator<char>(series)), std::istreambuf_iterator<char>());
    EXPECT_NE(listing.find("stress.vtu"), std::string::npos) << listing;
    EXPECT_NE(demeErrorMessage([&] { sim.WriteStressField(csv, lo, hi, 0, 1, 1); }).find("WriteStressField"),
              std::string::npos);
}
