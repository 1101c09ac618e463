// Brace lists of names, as the paper's listings write them (SetOutputContent({"XYZ", "ABSV"})),
// compile and mean the list, with one, two or three names: a list of two string literals would also
// make a std::string (the iterator-pair constructor), so an overload taking either could be ambiguous
// or, worse, read the two names as one string.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "ScratchDirTest.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

namespace {

class OutputContentList : public ScratchDirTest {
  protected:
    // The header row of the sphere file of a one-sphere scene whose content `choose` sets.
    std::string sphereHeader(const std::function<void(DEMSolver&)>& choose) {
        DEMSolver sim;
        sim.SetVerbosity("QUIET");
        choose(sim);
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
        sim.InstructBoxDomainDimension(1, 1, 1);
        sim.AddClumps(sim.LoadSphereType(1.f, 0.05f, mat), {make_float3(0, 0, 0)});
        sim.SetInitTimeStep(1e-4);
        sim.Initialize();
        const std::string path = (dir / ("spheres" + std::to_string(files++) + ".csv")).string();
        sim.WriteSphereFile(path);
        sim.FlushOutput();  // files are written by the writer thread
        std::ifstream in(path);
        std::string header;
        std::getline(in, header);
        return header;
    }
    int files = 0;
};

std::vector<std::string> names(std::initializer_list<const char*> list) { return {list.begin(), list.end()}; }

}  // namespace

// Columns come in the writer's order whatever the list's; XYZ is always written.
TEST_F(OutputContentList, OneTwoAndThreeNames) {
    EXPECT_EQ(sphereHeader([](DEMSolver& s) { s.SetOutputContent({"ABSV"}); }), "X,Y,Z,r,absv");
    EXPECT_EQ(sphereHeader([](DEMSolver& s) { s.SetOutputContent({"XYZ", "ABSV"}); }), "X,Y,Z,r,absv");
    EXPECT_EQ(sphereHeader([](DEMSolver& s) { s.SetOutputContent({"OWNER", "VEL"}); }), "X,Y,Z,r,v_x,v_y,v_z,owner");
    EXPECT_EQ(sphereHeader([](DEMSolver& s) { s.SetOutputContent({"XYZ", "ABSV", "FAMILY"}); }), "X,Y,Z,r,absv,family");
    // The other forms still mean what they meant: a string of names, a vector.
    EXPECT_EQ(sphereHeader([](DEMSolver& s) { s.SetOutputContent("XYZ ABSV"); }), "X,Y,Z,r,absv");
    EXPECT_EQ(sphereHeader([](DEMSolver& s) { s.SetOutputContent(std::vector<std::string>{"VEL"}); }),
              "X,Y,Z,r,v_x,v_y,v_z");
    EXPECT_EQ(sphereHeader([](DEMSolver& s) { s.SetOutputContent({}); }), "X,Y,Z,r");
    // A bad name in a two-name list is an error naming the call and the name.
    DEMSolver sim;
    const std::string msg = demeErrorMessage([&] { sim.SetOutputContent({"XYZ", "SPIN"}); });
    EXPECT_NE(msg.find("SetOutputContent"), std::string::npos) << msg;
    EXPECT_NE(msg.find("\"SPIN\""), std::string::npos) << msg;
}

// The force model's name lists take only a std::vector<std::string>, so a brace list is not
// ambiguous there; these check that one, two and three names are that many names.
TEST(ForceModelNameLists, OneTwoAndThreeNames) {
    DEMSolver sim;
    auto m = sim.DefineContactForceModel("force += make_float3(0.f, 0.f, 0.f);");
    m->SetMustHaveMatProp({"E"});
    EXPECT_EQ(m->GetMustHaveMatProp(), names({"E"}));
    m->SetMustHaveMatProp({"E", "nu"});
    EXPECT_EQ(m->GetMustHaveMatProp(), names({"E", "nu"}));
    m->SetMustHaveMatProp({"E", "nu", "CoR"});
    EXPECT_EQ(m->GetMustHaveMatProp(), names({"E", "nu", "CoR"}));
    m->SetMustPairwiseMatProp({"CoR", "mu"});
    EXPECT_EQ(m->GetMustPairwiseMatProp(), names({"CoR", "mu"}));
    m->SetPerContactWildcards({"delta_x", "delta_y"});
    EXPECT_EQ(m->GetPerContactWildcards(), names({"delta_x", "delta_y"}));
    m->SetPerOwnerWildcards({"Q", "charge"});
    EXPECT_EQ(m->GetPerOwnerWildcards(), names({"Q", "charge"}));
    m->SetPerGeometryWildcards({"g", "h"});
    EXPECT_EQ(m->GetPerGeometryWildcards(), names({"g", "h"}));
}
