// VTU output read back by meshio (tests/python/check_vtu.py): the same frame written as CSV and as
// VTU in every encoding (appended raw, base64, each with and without zlib) must give the same point
// count, the same coordinates and every array with the CSV's values; the .pvd series lists each
// frame with its simulated time. Runs on the backend in effect ($DEME_BACKEND), so on the GPU it
// checks that the writers see the device's current state.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "MeshBuilders.h"
#include "PythonCheck.h"
#include "ScratchDirTest.h"
#include "ForceModelTestUtil.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

namespace {

class VtuOutput : public ScratchDirTest {};

const char* VARIANTS[][3] = {{"raw", "appended", "none"},
                             {"rawzlib", "appended", "zlib"},
                             {"b64", "base64", "none"},
                             {"b64zlib", "base64", "zlib"}};

// Spheres and 2-sphere clumps resting on a plane (sphere-analytical contacts), touching each other
// (sphere-sphere) and on a small mesh floor (sphere-mesh), some moving and spinning, two families.
struct OutputScene {
    DEMSolver sim;
    explicit OutputScene(bool allContent) {
        sim.SetVerbosity("QUIET");
        if (allContent) sim.SetOutputContent("ABSV VEL ANG_VEL FAMILY OWNER MAT QUAT");
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5, 0.01));
        auto mat2 = sim.LoadMaterial(material(2e7, 0.3, 0.5, 0.5, 0.01));
        sim.InstructBoxDomainDimension(1, 1, 1);
        sim.AddBCPlane(make_float3(0, 0, -0.4f), make_float3(0, 0, 1), mat);
        sim.AddWavefrontMeshObject(gridFloor(0.1f, 0.1f, 0.f, 3, 0.1f, mat));
        auto ball = sim.LoadSphereType((float)sphereMass(0.02, 2600), 0.02f, mat);
        auto pair = sim.LoadClumpType((float)(2 * sphereMass(0.015, 2600)), make_float3(2e-6f, 4e-6f, 4e-6f),
                                      {0.015f, 0.015f}, {make_float3(-0.015f, 0, 0), make_float3(0.015f, 0, 0)},
                                      {mat, mat2});
        std::vector<float3> bed;
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) bed.push_back(make_float3(-0.4f + 0.039f * i, -0.1f + 0.039f * j, -0.381f));
        sim.AddClumps(ball, bed);
        sim.AddClumps(ball, {make_float3(0.2f, 0.2f, 0.019f), make_float3(0.239f, 0.2f, 0.019f)});
        auto falling = sim.AddClumps(pair, {make_float3(-0.3f, 0.2f, -0.2f), make_float3(0.f, 0.f, -0.2f)});
        falling->SetVel(std::vector<float3>{make_float3(0.3f, 0, -0.5f), make_float3(0, -0.2f, 0)});
        falling->SetAngVel(std::vector<float3>{make_float3(0, 0, 5.f), make_float3(3.f, 0, 0)});
        falling->SetFamily(3);
        sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
        sim.SetInitTimeStep(1e-5);
        sim.Initialize();
        sim.DoDynamics(0.002);
    }
};

void expectChecksPass(const std::string& args) {
    const ScriptResult r = runPythonCheck("check_vtu.py", args);
    EXPECT_EQ(r.status, 0) << "check_vtu.py " << args << ":\n" << r.output;
}

}  // namespace

TEST_F(VtuOutput, EveryEncodingReadsBackAsTheCsv) {
    OutputScene s(true);
    const std::string d = dir.string() + "/";
    s.sim.WriteSphereFile(d + "spheres.csv");
    s.sim.WriteClumpFile(d + "clumps.csv");
    s.sim.WriteContactFile(d + "contacts.csv");
    s.sim.WriteMeshFile(d + "mesh.vtk");
    s.sim.SetOutputFormat("VTU");
    s.sim.SetMeshOutputFormat("VTU");
    for (const auto& v : VARIANTS) {
        s.sim.SetVTUEncoding(v[1]);
        s.sim.SetVTUCompression(v[2]);
        const std::string suffix = std::string("_") + v[0] + ".vtu";
        s.sim.WriteSphereFile(d + "spheres" + suffix);
        s.sim.WriteClumpFile(d + "clumps" + suffix);
        s.sim.WriteContactFile(d + "contacts" + suffix);
        s.sim.WriteMeshFile(d + "mesh" + suffix);
    }
    s.sim.FlushOutput();
    // The frame has every kind of contact, so that every contact type code is checked.
    std::ifstream in(d + "contacts.csv");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* type : {"\nSS,", "\nSA,", "\nSM,"}) EXPECT_NE(text.find(type), std::string::npos) << type;
    expectChecksPass("frame " + dir.string() + " " + exactNumber(s.sim.GetSimTime()));
    // No temporary file is left behind.
    for (const auto& e : std::filesystem::directory_iterator(dir))
        EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

// Owner wildcard columns (EnableOwnerWildcardOutput) become Float32 arrays of their own names.
TEST_F(VtuOutput, OwnerWildcardArrays) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = useOwnerWildcardModel(sim);
    sim.InstructBoxDomainDimension(1, 1, 1);
    sim.AddClumps(sim.LoadSphereType(1.f, 0.01f, mat), {make_float3(0, 0, 0), make_float3(0.1f, 0, 0)});
    sim.SetInitTimeStep(1e-5);
    sim.EnableOwnerWildcardOutput();
    sim.Initialize();
    sim.SetOwnerWildcardValue("Q", 0, {0.25f, -2.f});
    const std::string d = dir.string() + "/";
    sim.WriteSphereFile(d + "spheres.csv");
    sim.WriteClumpFile(d + "clumps.csv");
    sim.SetOutputFormat("VTU");
    sim.WriteSphereFile(d + "spheres_raw.vtu");
    sim.WriteClumpFile(d + "clumps_raw.vtu");
    sim.FlushOutput();
    expectChecksPass("frame " + dir.string() + " " + exactNumber(sim.GetSimTime()));
}

TEST_F(VtuOutput, SeriesListsEachFrameWithItsTime) {
    OutputScene s(false);
    s.sim.SetOutputFormat("VTU");
    s.sim.SetMeshOutputFormat("VTU");
    const std::string d = dir.string() + "/";
    std::filesystem::create_directories(d + "frames");
    s.sim.SetOutputSeries("spheres", d + "spheres.pvd");
    s.sim.SetOutputSeries("meshes", d + "mesh.pvd");
    std::string times;
    for (int k = 0; k < 3; k++) {
        s.sim.DoDynamics(0.001);
        s.sim.WriteSphereFile(d + "frames/s_" + std::to_string(k) + ".vtu");
        s.sim.WriteMeshFile(d + "frames/m_" + std::to_string(k) + ".vtu");
        times += " " + exactNumber(s.sim.GetSimTime());
    }
    s.sim.FlushOutput();
    expectChecksPass("series " + d + "spheres.pvd" + times);
    expectChecksPass("series " + d + "mesh.pvd" + times);
    // Frames are listed relative to the .pvd, so that the folder can be moved as a whole.
    std::ifstream in(d + "spheres.pvd");
    const std::string pvd((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(pvd.find("file=\"frames/s_2.vtu\""), std::string::npos) << pvd;

    // A series lists VTU files only; ending it allows CSV again.
    s.sim.SetOutputFormat("CSV");
    const std::string msg = demeErrorMessage([&] { s.sim.WriteSphereFile(d + "x.csv"); });
    EXPECT_EQ(msg.rfind("WriteSphereFile:", 0), 0u) << msg;
    EXPECT_NE(msg.find("SetOutputFormat(\"VTU\")"), std::string::npos) << msg;
    s.sim.SetOutputSeries("spheres", "");
    s.sim.WriteSphereFile(d + "x.csv");
    s.sim.FlushOutput();
    EXPECT_TRUE(std::filesystem::exists(d + "x.csv"));
}

TEST(VtuOutputOptions, BadValuesNameTheCall) {
    DEMSolver sim;
    EXPECT_EQ(demeErrorMessage([&] { sim.SetOutputFormat("VTK"); }).rfind("SetOutputFormat:", 0), 0u);
    EXPECT_EQ(demeErrorMessage([&] { sim.SetMeshOutputFormat("CSV"); }).rfind("SetMeshOutputFormat:", 0), 0u);
    EXPECT_EQ(demeErrorMessage([&] { sim.SetVTUEncoding("ascii"); }).rfind("SetVTUEncoding:", 0), 0u);
    EXPECT_EQ(demeErrorMessage([&] { sim.SetVTUCompression("lzma"); }).rfind("SetVTUCompression:", 0), 0u);
    EXPECT_EQ(demeErrorMessage([&] { sim.SetOutputSeries("grains", "a.pvd"); }).rfind("SetOutputSeries:", 0), 0u);
}
