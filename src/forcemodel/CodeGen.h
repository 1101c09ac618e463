// The translation unit compiled at run time for a custom force model: the user's code as the body of
// a model functor that defines every variable the model may use (docs/force-models.md), instantiated
// in the engine's own force loop (backend/cpu/ForcePassLoop.h) and exported as an extern "C" force pass.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "forcemodel/ModelLayout.h"

namespace deme {

// Name of the exported force pass, of type ForcePassFunction (backend/cpu/ForcePass.h).
constexpr const char* kGeneratedForcePassSymbol = "deme_force_pass";

std::string generateForceModelSource(const ModelLayout& layout);

// The whole generated translation unit, shared by the CPU's and the GPU's generated code
// (CudaCodeGen.h): `banner` and the `includes`, then in namespace deme the model functor
// `UserForceModel` with its constants, members (material tables, wildcard arrays), `constructor` (the
// text that fills the members, which differs per backend) and its call operator, which declares the
// inputs and holds the user's code under `#line 1 "<origin>"` (after it, numbering returns to
// `generatedName`); last, outside the namespace, `entry` (the exported force pass).
std::string userForceModelSource(const ModelLayout& layout, const std::string& banner,
                                 const std::vector<std::string>& includes, const std::string& constructor,
                                 const std::string& generatedName, const std::string& entry);

}  // namespace deme
