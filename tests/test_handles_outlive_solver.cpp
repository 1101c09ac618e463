// Trackers and inspectors are shared handles a user may keep after the solver is gone (a Python
// script's variables, a C++ object destroyed out of order): using one then is a deme::Error that
// says so, never a read of freed memory.
#include <gtest/gtest.h>

#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

namespace {

struct Handles {
    std::shared_ptr<DEMTracker> tracker;
    std::shared_ptr<DEMInspector> inspector;
};

Handles handlesOfADestroyedSolver() {
    DEMSolver sim;
    sim.SetBackend("cpu");
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    sim.InstructBoxDomainDimension(1.f, 1.f, 1.f);
    auto batch = sim.AddClumps(sim.LoadSphereType(1.f, 0.01f, mat), {make_float3(0, 0, 0)});
    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    Handles h{sim.Track(batch), sim.CreateInspector("clump_max_z")};
    EXPECT_NEAR(h.tracker->Pos().z, 0.f, 1e-6f);  // alive while the solver is
    EXPECT_NEAR(h.inspector->GetValue(), 0.0, 1e-6);
    return h;
}

}  // namespace

TEST(HandlesOutliveSolver, TrackerCallsAreErrors) {
    const Handles h = handlesOfADestroyedSolver();
    for (const std::string& msg :
         {demeErrorMessage([&] { h.tracker->Pos(); }), demeErrorMessage([&] { h.tracker->Vel(); }),
          demeErrorMessage([&] { h.tracker->SetPos(make_float3(0.f)); }),
          demeErrorMessage([&] { h.tracker->GetOwnerID(); }),
          demeErrorMessage([&] { h.tracker->AddAcc(make_float3(0.f)); })})
        EXPECT_NE(msg.find("the solver this tracker belongs to has been destroyed"), std::string::npos) << msg;
    EXPECT_EQ(h.tracker->GetNumOwners(), 1u);  // what the handle itself knows stays readable
}

TEST(HandlesOutliveSolver, InspectorCallsAreErrors) {
    const Handles h = handlesOfADestroyedSolver();
    const std::string msg = demeErrorMessage([&] { h.inspector->GetValue(); });
    EXPECT_NE(msg.find("DEMInspector::GetValue: the solver this inspector belongs to has been destroyed"),
              std::string::npos)
        << msg;
}
