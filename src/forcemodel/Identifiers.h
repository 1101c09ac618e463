// Names a user gives to material properties and wildcards become C++ variables of a force model:
// they must be identifiers and must not hide what the model already sees (paper Table 3, helpers).
#pragma once

#include <string>

namespace deme {

bool isCppIdentifier(const std::string& name);

// Why `name` cannot name a user variable of a force model ("a C++ keyword", "a variable every force
// model already has (contactPnt, B2A, ...)", ...), or "" if it can.
std::string reservedNameReason(const std::string& name);

}  // namespace deme
