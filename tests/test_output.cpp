// Output files: header rows, user order of rows and ids (owners are stored in a different,
// space-filling order internally), and values that can be checked by hand.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(Output);

namespace {

std::vector<std::vector<std::string>> readCsv(const std::string& path) {
    std::ifstream f(path);
    std::vector<std::vector<std::string>> rows;
    std::string line;
    while (std::getline(f, line)) {
        std::vector<std::string> cells;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) cells.push_back(cell);
        rows.push_back(cells);
    }
    return rows;
}

}  // namespace

DEME_BACKEND_TEST(Output, FilesListOwnersInUserOrderWithHeaders) {
    const std::string dir = scratchDir().string();
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    sim.SetOutputContent({"ABSV", "VEL", "OWNER", "FAMILY"});
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    sim.InstructBoxDomainDimension(1, 1, 1);
    sim.AddBCPlane(make_float3(0, 0, -0.4f), make_float3(0, 0, 1), mat);
    auto sphere = sim.LoadSphereType(1.f, 0.05f, mat);
    auto pair = sim.LoadClumpType(2.f, make_float3(0.01f), {0.05f, 0.05f},
                                  {make_float3(-0.05f, 0, 0), make_float3(0.05f, 0, 0)}, mat);
    // Added far from space-filling-curve order: the last clump is the one nearest the origin corner.
    auto a = sim.AddClumps(sphere, {make_float3(0.4f, 0.4f, 0.4f), make_float3(0, 0, -0.36f)});
    auto b = sim.AddClumps(pair, {make_float3(-0.4f, -0.4f, -0.2f)});
    a->SetVel(std::vector<float3>{make_float3(1, 0, 0), make_float3(0, 0, 0)});
    b->SetFamily(3);
    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    sim.DoStepDynamics();
    sim.WriteSphereFile(dir + "/spheres.csv");
    sim.WriteClumpFile(dir + "/clumps.csv");
    sim.WriteContactFile(dir + "/contacts.csv");
    sim.FlushOutput();  // files are written in the background

    const auto sph = readCsv(dir + "/spheres.csv");
    ASSERT_EQ(sph.size(), 5u);  // header + 1 + 1 + 2 spheres
    EXPECT_EQ(sph[0], (std::vector<std::string>{"X", "Y", "Z", "r", "absv", "v_x", "v_y", "v_z", "family", "owner"}));
    EXPECT_NEAR(std::stod(sph[1][0]), 0.4, 1e-4);  // first clump added
    EXPECT_NEAR(std::stod(sph[1][4]), 1.0, 1e-6);  // its speed
    EXPECT_EQ(sph[1][9], "0");
    EXPECT_EQ(sph[2][9], "1");
    EXPECT_NEAR(std::stod(sph[3][0]), -0.45, 1e-4);  // the pair's spheres in template order
    EXPECT_NEAR(std::stod(sph[4][0]), -0.35, 1e-4);
    EXPECT_EQ(sph[3][8], "3");
    EXPECT_EQ(sph[4][9], "2");

    const auto clumps = readCsv(dir + "/clumps.csv");
    ASSERT_EQ(clumps.size(), 4u);
    EXPECT_EQ(clumps[0][0], "owner");
    EXPECT_EQ(clumps[3][0], "2");
    EXPECT_NEAR(std::stod(clumps[3][1]), -0.4, 1e-5);
    EXPECT_NEAR(std::stod(clumps[3][14]), 2.0, 1e-6);  // mass
    EXPECT_EQ(clumps[3][15], "3");                     // family

    // The second sphere (user sphere id 1, owner 1) rests 1 cm into the plane z = -0.4: one SA contact.
    const auto contacts = readCsv(dir + "/contacts.csv");
    ASSERT_EQ(contacts.size(), 2u);
    EXPECT_EQ(contacts[0][0], "type");
    EXPECT_EQ(contacts[1][0], "SA");
    EXPECT_EQ(contacts[1][1], "1");                       // geomA: user sphere id
    EXPECT_EQ(contacts[1][3], "1");                       // ownerA: user owner id
    EXPECT_EQ(contacts[1][4], "3");                       // ownerB: the plane object, after the three clumps
    EXPECT_NEAR(std::stod(contacts[1][14]), 0.01, 1e-4);  // overlap
    EXPECT_GT(std::stod(contacts[1][10]), 0.0);           // pushed up
}
