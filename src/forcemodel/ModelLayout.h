// What a force model reads, laid out for the engine: the model's kind and source, the material
// properties it sees per material and per pair, and its wildcards, in the order of the state's
// tables (SimState::materials, SimState::wildcards, ContactArrays::wildcards). Resolved from the
// user's scene by api/ForceModelSetup.h.
#pragma once

#include <string>
#include <vector>

#include <deme/ForceModel.h>

namespace deme {

struct ModelLayout {
    DEMForceModel::Kind kind = DEMForceModel::Kind::FRICTIONAL_HERTZIAN;
    std::string source, origin;              // a custom model's code, and its name in compiler messages
    std::vector<std::string> materialProps;  // name[bodyAMatType]
    std::vector<std::string> pairProps;      // name[bodyAMatType][bodyBMatType]
    std::vector<std::string> contactWildcards, ownerWildcards, geometryWildcards;
    bool calledForApartPairs = true;         // DEMForceModel::SetCalledForApartPairs

    bool builtIn() const { return kind != DEMForceModel::Kind::CUSTOM; }
    // "the frictional Hertzian model", "the custom force model", for messages.
    std::string description() const;
};

// Index of `name` in `list`, or -1.
int indexOf(const std::vector<std::string>& list, const std::string& name);

}  // namespace deme
