// Helpers shared by the force model tests (test_force_models*.cpp).
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include <deme/deme.h>

#include "TestHelpers.h"
#include "jit/EmbeddedSources.h"

namespace deme_test {

// The text of an embedded source, e.g. the default model's body "physics/models/HertzMindlin.inl".
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

}  // namespace deme_test
