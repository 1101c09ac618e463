// WriteSnapshot: the PNG decodes with PIL (tests/python/check_png.py) to the requested size; a bed
// seen from the side shows grain colour below its top and background above it (the rows computed
// here from the zoom box, which maps onto the image exactly); coloured by height it runs from the
// colour map's low end at the bottom to its high end at the top; seen from above, a mesh floor
// shows around the bed; coloured by an owner wildcard, its values map onto the colour map. Runs on
// the backend in effect ($DEME_BACKEND).
#include <gtest/gtest.h>

#include <algorithm>

#include "MeshBuilders.h"
#include "PythonCheck.h"
#include "ScratchDirTest.h"
#include "ForceModelTestUtil.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

namespace {

const float R = 0.005f;

// An HCP block of overlapping spheres (centres 1.5 r apart, so the block has no gaps seen from any
// side), never stepped: the positions are the sampler's. A mesh floor just below it.
struct Bed {
    DEMSolver sim;
    std::shared_ptr<DEMClumpBatch> grains;
    float minX = 1e9f, maxX = -1e9f, minZ = 1e9f, maxZ = -1e9f;
    Bed() {
        sim.SetVerbosity("QUIET");
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
        sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.2f);
        sim.AddWavefrontMeshObject(gridFloor(-0.09f, -0.09f, 0.001f, 6, 0.03f, mat));
        const auto pts =
            HCPSampler(1.5f * R).SampleBox(make_float3(0, 0, 0.03f), make_float3(0.04f, 0.02f, 0.02f));
        grains = sim.AddClumps(sim.LoadSphereType(1e-3f, R, mat), pts);
        grains->SetFamily(2);
        sim.SetInitTimeStep(1e-5);
        sim.Initialize();
        auto tr = sim.Track(grains);
        for (size_t i = 0; i < pts.size(); i++) {
            const float3 p = tr->Pos(i);
            minX = std::min(minX, p.x), maxX = std::max(maxX, p.x), minZ = std::min(minZ, p.z), maxZ = std::max(maxZ, p.z);
        }
    }
};

class Snapshot : public ScratchDirTest {};

void expectPng(const std::string& args) {
    const ScriptResult r = runPythonCheck("check_png.py", args);
    EXPECT_EQ(r.status, 0) << "check_png.py " << args << ":\n" << r.output;
}

std::string num(double v) { return exactNumber(v); }

}  // namespace

TEST_F(Snapshot, BedFromTheSideShowsGrainBelowItsTopAndBackgroundAbove) {
    Bed bed;
    // Looking along +y at x in [-0.05, 0.05], z in [0, 0.075]: 4:3, so 400 x 300 pixels map it exactly,
    // 4000 pixels per metre, row = (0.075 - z) * 4000, column = (x + 0.05) * 4000.
    SnapshotOptions o;
    o.width = 400, o.height = 300;
    o.direction = make_float3(0, 1, 0);
    o.boxMin = make_float3(-0.05f, -0.1f, 0.f), o.boxMax = make_float3(0.05f, 0.1f, 0.075f);
    o.colorBy = "none";
    const std::string side = (dir / "side.png").string(), height = (dir / "height.png").string();
    bed.sim.WriteSnapshot(side, o);
    o.colorBy = "height";
    o.colorBar = false;
    bed.sim.WriteSnapshot(height, o);
    bed.sim.FlushOutput();
    const double s = 4000.0;
    const std::string rows = num((0.075 - bed.maxZ) * s) + " " + num((0.075 - bed.minZ) * s) + " " +
                             num((bed.minX + 0.05) * s) + " " + num((bed.maxX + 0.05) * s);
    expectPng("bed " + side + " 400 300 " + num((0.075 - bed.maxZ - R) * s) + " " + rows + " 255,255,255");
    expectPng("height " + height + " 400 300 " + rows);
}

TEST_F(Snapshot, DefaultsAndOtherColoursDecodeToTheRequestedSize) {
    Bed bed;
    bed.sim.DoDynamics(1e-4);  // speeds to colour by
    const std::string a = (dir / "default.png").string(), b = (dir / "family.png").string();
    bed.sim.WriteSnapshot(a);
    SnapshotOptions o;
    o.width = 333, o.height = 211;
    o.colorBy = "family";
    o.background = {30, 30, 40};
    bed.sim.WriteSnapshot(b, o);
    bed.sim.FlushOutput();
    expectPng("size " + a + " 1280 720");
    expectPng("size " + b + " 333 211");
}

// From above: the floor mesh around the bed, the bed in the middle, background beyond the floor.
TEST_F(Snapshot, MeshFloorAroundTheBedFromAbove) {
    Bed bed;
    SnapshotOptions o;
    o.width = 400, o.height = 300;
    o.direction = make_float3(0, 0, -1);  // x to the right, y up in the picture
    o.boxMin = make_float3(-0.1f, -0.075f, -0.01f), o.boxMax = make_float3(0.1f, 0.075f, 0.1f);
    o.colorBy = "none";
    const std::string top = (dir / "top.png").string();
    bed.sim.WriteSnapshot(top, o);
    bed.sim.FlushOutput();
    // Column = (x + 0.1) * 2000, row = (0.075 - y) * 2000.
    expectPng("pixels " + top + " 400 300 200,150,grain 340,50,mesh 60,250,mesh 390,10,bg 5,295,bg");
}

// Colour by an owner wildcard of the force model over a given range: the owner at the range's
// bottom is drawn in the colour map's low end, the one at its top in the high end.
TEST_F(Snapshot, ColourByAnOwnerWildcard) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = useOwnerWildcardModel(sim);
    sim.InstructBoxDomainDimension(1, 1, 1);
    sim.AddClumps(sim.LoadSphereType(1.f, 0.01f, mat), {make_float3(-0.02f, 0, 0), make_float3(0.02f, 0, 0)});
    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    sim.SetOwnerWildcardValue("Q", 0, {0.f, 1.f});
    SnapshotOptions o;
    o.width = 400, o.height = 200;  // x in [-0.04, 0.04], z in [-0.02, 0.02]: 5000 pixels per metre
    o.direction = make_float3(0, 1, 0);
    o.boxMin = make_float3(-0.04f, -0.1f, -0.02f), o.boxMax = make_float3(0.04f, 0.1f, 0.02f);
    o.colorBy = "Q";
    o.colorMin = 0.f, o.colorMax = 1.f;
    o.colorBar = false;
    const std::string path = (dir / "wildcard.png").string();
    sim.WriteSnapshot(path, o);
    sim.FlushOutput();
    // Sphere centres at columns 100 and 300 of row 100; the gap between them at column 200.
    expectPng("pixels " + path + " 400 200 100,100,low 300,100,high 200,100,bg");
}

TEST(SnapshotOptionsCheck, BadOptionsNameTheCall) {
    Bed bed;
    auto msg = [&](const SnapshotOptions& o) { return demeErrorMessage([&] { bed.sim.WriteSnapshot("/tmp/x.png", o); }); };
    SnapshotOptions o;
    o.colorBy = "temperature";
    const std::string m = msg(o);
    EXPECT_EQ(m.rfind("WriteSnapshot:", 0), 0u) << m;
    EXPECT_NE(m.find("temperature"), std::string::npos) << m;
    o = SnapshotOptions();
    o.width = 0;
    EXPECT_EQ(msg(o).rfind("WriteSnapshot:", 0), 0u);
    o = SnapshotOptions();
    o.direction = make_float3(0, 0, 0);
    EXPECT_NE(msg(o).find("direction"), std::string::npos);
    o = SnapshotOptions();
    o.boxMax = make_float3(1, 1, 0);
    EXPECT_NE(msg(o).find("zoom box"), std::string::npos);
    DEMSolver fresh;
    EXPECT_EQ(demeErrorMessage([&] { fresh.WriteSnapshot("/tmp/x.png"); }).rfind("WriteSnapshot:", 0), 0u);
}
