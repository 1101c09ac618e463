#include "api/WildcardLookup.h"

#include <deme/Error.h>

#include "runtime/Simulation.h"

namespace deme {

unsigned int wildcardIndex(const Simulation& sim, const char* call, WildcardKind kind, const std::string& name) {
    const ModelLayout& L = sim.forceModel();
    const std::vector<std::string>& list = kind == WildcardKind::CONTACT ? L.contactWildcards
                                           : kind == WildcardKind::OWNER ? L.ownerWildcards
                                                                         : L.geometryWildcards;
    const int i = indexOf(list, name);
    if (i >= 0) return (unsigned int)i;
    const char* what = kind == WildcardKind::CONTACT ? "Contact" : kind == WildcardKind::OWNER ? "Owner" : "Geometry";
    std::string known;
    for (const auto& n : list) known += (known.empty() ? "" : ", ") + n;
    std::string lower = what;
    lower[0] = (char)(lower[0] - 'A' + 'a');
    throwError(call, "the force model has no " + lower + " wildcard \"" + name + "\" (" +
                         (known.empty() ? std::string("it has none") : "it has: " + known) +
                         "; declare them with SetPer" + what + "Wildcards)");
}

}  // namespace deme
