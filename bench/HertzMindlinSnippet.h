// The default Hertz-Mindlin model written out as a custom model's code (its history cleared when a
// pair is apart, as the built-in model does), for the model-compile benchmarks. Needs DEME_SOURCE_DIR.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include <deme/DEMSolver.h>
#include <deme/Error.h>

namespace deme_bench {

inline std::string hertzMindlinSnippet() {
    std::ifstream in(DEME_SOURCE_DIR "/src/physics/models/HertzMindlin.inl");
    if (!in) throw deme::Error("cannot read HertzMindlin.inl from " DEME_SOURCE_DIR);
    std::ostringstream s;
    s << "if (!(overlapDepth > 0.0)) {\n"
         "    delta_tan_x = delta_tan_y = delta_tan_z = delta_time = 0.f;\n"
         "    return;\n"
         "}\n"
      << in.rdbuf();
    return s.str();
}

// Makes the snippet `sim`'s contact force model, with the inputs the built-in model has; returns it.
inline std::shared_ptr<deme::DEMForceModel> useHertzMindlinSnippet(deme::DEMSolver& sim) {
    auto m = sim.DefineContactForceModel(hertzMindlinSnippet());
    m->SetMustHaveMatProp({"E", "nu", "CoR", "mu", "Crr"});
    m->SetMustPairwiseMatProp({"CoR", "mu", "Crr"});
    m->SetPerContactWildcards({"delta_tan_x", "delta_tan_y", "delta_tan_z", "delta_time"});
    return m;
}

}  // namespace deme_bench
