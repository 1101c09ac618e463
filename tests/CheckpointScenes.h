// Scenes for the checkpoint tests (test_checkpoint.cpp) and for the program that runs them in a
// process of its own (tools/checkpoint_run.cpp): one function builds the scene up to Initialize(),
// as a restarted script would.
#pragma once

#include <memory>
#include <string>

#include <deme/deme.h>

namespace deme_test {

struct CheckpointScene {
    bool async = false;        // asynchronous contact detection (the CPU is deterministic in both modes)
    bool shaken = false;       // the container moves with a prescribed velocity of t
    bool customModel = false;  // Hertz-Mindlin plus a contact, an owner and a geometry wildcard
    std::string backend = "cpu";
    double mu = 0.5;  // the grains' friction coefficient (another value is another scene)
};

// The default Hertz-Mindlin model (tangential history in four contact wildcards) with an extra
// contact wildcard `age` (steps in touch, reset apart), and an owner wildcard Q and a geometry
// wildcard g that scale the force: each must be restored for the run to go on bit for bit.
inline const char* const kCheckpointModelTail = R"(
if (overlapDepth > 0.0) age += 1.f; else age = 0.f;
)";
inline const char* const kCheckpointModelScale = R"(
force *= (1.f + 0.05f * Q[AOwner] + 0.05f * g[AGeo] + 1e-4f * fminf(age, 100.f));
)";

// About 200 two-sphere clumps poured into a box with a floor and four walls; returns the batch.
inline std::shared_ptr<deme::DEMClumpBatch> buildCheckpointScene(deme::DEMSolver& sim, const CheckpointScene& sc,
                                                                 const std::string& hertzMindlinBody = "") {
    using namespace deme;
    sim.SetVerbosity("QUIET");
    sim.SetProgressReport(false);
    sim.SetBackend(sc.backend);
    auto mat = sim.LoadMaterial({{"E", 1e7}, {"nu", 0.3}, {"CoR", 0.4}, {"mu", sc.mu}, {"Crr", 0.01}});
    if (sc.customModel) {
        auto model = sim.DefineContactForceModel(std::string(kCheckpointModelTail) + hertzMindlinBody +
                                                 kCheckpointModelScale);
        model->SetMustHaveMatProp({"E", "nu", "CoR", "mu", "Crr"});
        model->SetMustPairwiseMatProp({"CoR", "mu", "Crr"});
        model->SetPerContactWildcards({"delta_tan_x", "delta_tan_y", "delta_tan_z", "delta_time", "age"});
        model->SetPerOwnerWildcards({"Q"});
        model->SetPerGeometryWildcards({"g"});
    }
    sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.2f);
    auto box = sim.AddExternalObject();
    box->AddPlane(make_float3(0, 0, -0.05f), make_float3(0, 0, 1), mat);
    box->AddPlane(make_float3(-0.03f, 0, 0), make_float3(1, 0, 0), mat);
    box->AddPlane(make_float3(0.03f, 0, 0), make_float3(-1, 0, 0), mat);
    box->AddPlane(make_float3(0, -0.03f, 0), make_float3(0, 1, 0), mat);
    box->AddPlane(make_float3(0, 0.03f, 0), make_float3(0, -1, 0), mat);
    if (sc.shaken) {
        box->SetFamily(5);
        sim.SetFamilyPrescribedLinVel(5, "0.2*sin(300*t)", "0", "0.3*cos(250*t)");
    }
    auto tmpl = sim.LoadClumpType(2e-3f, make_float3(1e-8f, 1.2e-8f, 1.4e-8f), {0.003f, 0.0025f},
                                  {make_float3(0.001f, 0, 0), make_float3(-0.002f, 0, 0)}, mat);
    auto pts = HCPSampler(0.0082f).SampleBox(make_float3(0, 0, -0.035f), make_float3(0.025f, 0.025f, 0.012f));
    auto batch = sim.AddClumps(tmpl, pts);
    sim.SetInitTimeStep(2e-5);
    sim.SetCDUpdateFreq(15);
    // Synchronous mode with a fixed n_max: detections fall on the same steps in every run (an
    // adaptive n_max follows measured wall times), so the contact set itself, near pairs included,
    // is the same too, and so are the pairs MarkPersistentContact marks.
    if (!sc.async) sim.DisableAdaptiveUpdateFreq();
    sim.SetSynchronousContactDetection(!sc.async);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.Initialize();
    return batch;
}

// Steps the scene through its script: a first phase, then (before any checkpoint is taken) the
// edits a running script makes between calls, so that the checkpoint must carry them.
inline void checkpointScenePhase1(deme::DEMSolver& sim, const CheckpointScene& sc, size_t steps) {
    for (size_t k = 0; k + 1 < steps; k++) sim.DoStepDynamics();
    if (sc.customModel) {
        for (size_t o = 0; o < sim.GetNumClumps(); o += 3) sim.SetOwnerWildcardValue("Q", o, 0.5f + 0.01f * (float)o);
        for (size_t s = 0; s < sim.GetNumSpheres(); s += 5) sim.SetSphereWildcardValue("g", s, 0.3f);
        sim.MarkPersistentContact();
    }
    sim.UpdateStepSize(1.5e-5);
    sim.SetGravitationalAcceleration(deme::make_float3(0.5f, 0, -9.81f));
    sim.DoStepDynamics();  // the edits above re-detect here: the checkpoint then has a set in use
}

}  // namespace deme_test
