// Finds a force model wildcard by the name the user gave it, for the host-side wildcard API.
#pragma once

#include <string>

namespace deme {

class Simulation;

enum class WildcardKind { CONTACT, OWNER, GEOMETRY };

// Index of the wildcard in its list (SimState::wildcards, ContactArrays::wildcards). An unknown name is
// a deme::Error naming `call` and listing the model's wildcards of that kind.
unsigned int wildcardIndex(const Simulation& sim, const char* call, WildcardKind kind, const std::string& name);

}  // namespace deme
