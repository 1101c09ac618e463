// Helpers shared by the force model tests (test_force_models*.cpp).
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include <deme/deme.h>

#include "TestHelpers.h"
#include "backend/cuda/Device.h"
#include "jit/EmbeddedSources.h"

namespace deme_test {

// The text of an embedded source, e.g. the default model's body "physics/models/HertzMindlin.inl".
// An owner wildcard "Q" (with contact wildcard "c" and geometry wildcard "g") on a model that
// exerts no force, and the material it reads: the names of test_force_models_errors.cpp, so that the
// generated code is the same and compiled once. Returns the material.
inline std::shared_ptr<DEMMaterial> useOwnerWildcardModel(DEMSolver& sim) {
    auto mat = sim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}});
    auto model = sim.DefineContactForceModel("force += make_float3(0.f, 0.f, 0.f);");
    model->SetPerContactWildcards({"c"});
    model->SetPerOwnerWildcards({"Q"});
    model->SetPerGeometryWildcards({"g"});
    return mat;
}

inline std::string embeddedText(const std::string& path) {
    for (const deme::jit::EmbeddedFile& f : deme::jit::embeddedSources())
        if (path == f.path) return std::string(f.text, f.size);
    ADD_FAILURE() << "no embedded source " << path;
    return "";
}

// The default Hertz-Mindlin model written out as a custom model: the built-in loop gives pairs that
// are apart no call, zero force and cleared history; a custom model sees them and does that itself.
inline std::string hertzMindlinSnippet() {
    return "if (!(overlapDepth > 0.0)) {\n"
           "    delta_tan_x = 0.f;\n"
           "    delta_tan_y = 0.f;\n"
           "    delta_tan_z = 0.f;\n"
           "    delta_time = 0.f;\n"
           "    return;\n"
           "}\n" +
           embeddedText("physics/models/HertzMindlin.inl");
}

// Declares on `model` what the default model reads (as the built-in model does).
inline void declareHertzMindlinInputs(deme::DEMForceModel& model) {
    model.SetMustHaveMatProp({"E", "nu", "CoR", "mu", "Crr"});
    model.SetMustPairwiseMatProp({"CoR", "mu", "Crr"});
    model.SetPerContactWildcards({"delta_tan_x", "delta_tan_y", "delta_tan_z", "delta_time"});
}

// Whether the CUDA backend can run here; the force model tests that compare the GPU with the CPU
// (GpuParity.*) skip themselves otherwise (CI), and tests/gpu/run.sh runs them on a GPU machine.
inline bool gpuPresent() { return deme::cuda::cudaBackendBuilt() && !deme::cuda::usableDevices().empty(); }

// Custom models shared by the force model tests (backend tests and GpuParity.* comparisons).

// Coulomb's force between the owners' charges Q (an owner wildcard), for every pair in the contact set
// whether or not it touches.
inline const char* const kElectrostatic = R"(
const double3 d = bodyAPos - bodyBPos;
const double r = length(d);
const double magnitude = 8.9875517923e9 * (double)Q[AOwner] * (double)Q[BOwner] / (r * r);
force += to_float3(d * (magnitude / r));
)";

// Counts the steps a pair has overlapped since it entered the contact set, and shows the count on
// both owners (an owner wildcard the model writes: one writing contact per owner here).
inline const char* const kAgeCounter = R"(
if (overlapDepth > 0.0) age += 1.f;
ageSeen[AOwner] = age;
ageSeen[BOwner] = age;
)";

// DMT (Derjaguin-Muller-Toporov) adhesion: the Hertz force of the default model (with its CoR
// damping) minus a constant pull 2 pi W R while the surfaces overlap, W being the work of adhesion of
// the material pair. A sphere under a ceiling hangs while m g < 2 pi W R, the DMT pull-off force, at
// the overlap where the Hertz force 4/3 E* sqrt(R) d^(3/2) equals 2 pi W R - m g.
inline const char* const kDMT = R"(
if (overlapDepth > 0.0) {
    const float R = ARadius * BRadius / (ARadius + BRadius);
    const float m = AOwnerMass * BOwnerMass / (AOwnerMass + BOwnerMass);
    const float Sn = 2.f * E_eff[bodyAMatType][bodyBMatType] * sqrtf(R * (float)overlapDepth);
    const float vn = dot((ALinVel + rotVelCPA) - (BLinVel + rotVelCPB), B2A);
    const float damping = 2.f * sqrtf(5.f / 6.f) * beta_CoR[bodyAMatType][bodyBMatType] * sqrtf(Sn * m);
    const float pull = 2.f * (float)deme::PI * W[bodyAMatType][bodyBMatType] * R;
    force += (2.f / 3.f * Sn * (float)overlapDepth + damping * vn - pull) * B2A;
}
)";

}  // namespace deme_test
