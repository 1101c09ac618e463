// GetDEMEDataFile: the shipped data files are found (from this build, the source tree's data/),
// DEME_DATA_DIR comes first, and a missing file is an error naming it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "ScratchDirTest.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;
namespace fs = std::filesystem;

TEST(DataFiles, ShippedFilesAreFoundAndLoad) {
    const std::string obj = GetDEMEDataFile("mesh/internal_mixer.obj");
    const std::string csv = GetDEMEDataFile("clumps/3_clump.csv");
    EXPECT_TRUE(fs::path(obj).is_absolute());
    EXPECT_TRUE(fs::is_regular_file(obj) && fs::is_regular_file(csv));
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e8, 0.3, 0.5, 0.5));
    EXPECT_EQ(sim.AddWavefrontMeshObject(obj, mat)->GetNumTriangles(), 176u);
    auto tmpl = sim.LoadClumpType(5.5886717f, make_float3(2.928f, 2.6029f, 3.9908f), csv, mat);
    EXPECT_EQ(tmpl->GetNumSpheres(), 3u);
    EXPECT_FLOAT_EQ(tmpl->radii[0], 0.8f);
}

TEST(DataFiles, MissingFileNamesItAndTheFolders) {
    const std::string msg = demeErrorMessage([] { GetDEMEDataFile("mesh/none.obj"); });
    EXPECT_EQ(msg.rfind("GetDEMEDataFile: no data file \"mesh/none.obj\" in ", 0), 0u) << msg;
    EXPECT_NE(msg.find("DEME_DATA_DIR"), std::string::npos);
    EXPECT_NE(demeErrorMessage([] { GetDEMEDataFile(""); }).find("empty"), std::string::npos);
    EXPECT_NE(demeErrorMessage([] { GetDEMEDataFile("/etc/hosts"); }).find("absolute"), std::string::npos);
}

class DataFilesDir : public ScratchDirTest {};

TEST_F(DataFilesDir, DataDirVariableComesFirst) {
    fs::create_directories(dir / "mesh");
    std::ofstream(dir / "mesh" / "internal_mixer.obj") << "v 0 0 0\n";
    setenv("DEME_DATA_DIR", dir.c_str(), 1);
    const std::string found = GetDEMEDataFile("mesh/internal_mixer.obj");
    const auto dirs = GetDEMEDataDirs();
    const std::string clump = GetDEMEDataFile("clumps/3_clump.csv");  // not there: the next folders
    unsetenv("DEME_DATA_DIR");
    EXPECT_EQ(found, (dir / "mesh" / "internal_mixer.obj").string());
    ASSERT_FALSE(dirs.empty());
    EXPECT_EQ(dirs.front(), dir.string());
    EXPECT_TRUE(fs::is_regular_file(clump));
}
