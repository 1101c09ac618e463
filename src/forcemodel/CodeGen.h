// The translation unit compiled at run time for a custom force model: the user's code as the body of
// a model functor that defines every variable the model may use (docs/force-models.md), instantiated
// in the engine's own force loop (dynamics/ForcePassLoop.h) and exported as an extern "C" force pass.
#pragma once

#include <string>

#include "forcemodel/ModelLayout.h"

namespace deme {

// Name of the exported force pass, of type ForcePassFunction (dynamics/ForcePass.h).
constexpr const char* kGeneratedForcePassSymbol = "deme_force_pass";

std::string generateForceModelSource(const ModelLayout& layout);

}  // namespace deme
