// The built-in frictionless Hertzian model (UseFrictionlessHertzianModel), and owner wildcard columns in
// the output files.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "BackendFixture.h"
#include "ForceModelTestUtil.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(ForceModelFrictionless);
DEME_BACKEND_TEST_SUITE(ForceModelOutput);

// A sphere hits a plane obliquely (1 m/s down, 0.5 m/s along x) with mu = 0.5 in the materials: the
// frictionless model ignores mu, so the tangential velocity comes out exactly as it went in and the
// sphere does not spin; the normal rebound speed over the impact speed is the CoR (5 %, as the default
// model's HertzImpact test, since both share the normal force). On the GPU: the frictionless kernel
// built into the GPU's dynamics module.
DEME_BACKEND_TEST(ForceModelFrictionless, ObliqueImpactKeepsTangentialVelocity) {
    const double r = 0.01, density = 2600, E = 1e8, nu = 0.3, cor = 0.5, v = 1.0;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(E, nu, cor, 0.5, 0.1));
    auto model = sim.UseFrictionlessHertzianModel();
    EXPECT_EQ(model->GetKind(), DEMForceModel::Kind::FRICTIONLESS_HERTZIAN);
    EXPECT_TRUE(model->GetPerContactWildcards().empty());
    sim.InstructBoxDomainDimension(1, 1, 1);
    sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    auto ball = sim.AddClumps(sim.LoadSphereType((float)sphereMass(r, density), (float)r, mat),
                              {make_float3(0, 0, (float)(r + 1e-4))});
    ball->SetVel(std::vector<float3>{make_float3(0.5f, 0, (float)-v)});
    sim.SetInitTimeStep(1e-6);
    sim.Initialize();
    auto tr = sim.Track(ball);
    bool touched = false;
    for (int i = 0; i < 1000 && !(touched && sim.GetNumContacts() == 0); i++) {
        sim.DoDynamics(1e-5);
        touched |= sim.GetNumContacts() > 0;
    }
    ASSERT_TRUE(touched);
    EXPECT_NEAR(tr->Vel().z / v, cor, 0.05 * cor);
    EXPECT_EQ(tr->Vel().x, 0.5f);
    EXPECT_EQ(tr->AngVelGlobal().y, 0.f);
}

// EnableOwnerWildcardOutput: a column per owner wildcard, with each owner's value, in the clump file
// and (the sphere's owner's value) in the sphere file.
DEME_BACKEND_TEST(ForceModelOutput, OwnerWildcardColumns) {
    const std::filesystem::path dir = scratchDir();
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = useOwnerWildcardModel(sim);
    sim.InstructBoxDomainDimension(1, 1, 1);
    auto tmpl = sim.LoadSphereType(1.f, 0.01f, mat);
    sim.AddClumps(tmpl, {make_float3(0, 0, 0), make_float3(0.1f, 0, 0)});
    sim.SetInitTimeStep(1e-5);
    sim.EnableOwnerWildcardOutput();
    sim.Initialize();
    sim.SetOwnerWildcardValue("Q", 0, {0.25f, -2.f});
    sim.WriteClumpFile((dir / "clumps.csv").string());
    sim.WriteSphereFile((dir / "spheres.csv").string());
    sim.FlushOutput();  // files are written in the background
    auto lines = [](const std::filesystem::path& p) {
        std::ifstream in(p);
        std::vector<std::string> v;
        for (std::string l; std::getline(in, l);) v.push_back(l);
        return v;
    };
    const auto clumps = lines(dir / "clumps.csv"), spheres = lines(dir / "spheres.csv");
    ASSERT_EQ(clumps.size(), 3u);
    EXPECT_EQ(clumps[0], "owner,X,Y,Z,Qw,Qx,Qy,Qz,v_x,v_y,v_z,w_x,w_y,w_z,mass,family,Q");
    EXPECT_EQ(clumps[1].substr(clumps[1].rfind(',')), ",0.25");
    EXPECT_EQ(clumps[2].substr(clumps[2].rfind(',')), ",-2");
    ASSERT_EQ(spheres.size(), 3u);
    EXPECT_EQ(spheres[0], "X,Y,Z,r,Q");
    EXPECT_EQ(spheres[2].substr(spheres[2].rfind(',')), ",-2");
}
