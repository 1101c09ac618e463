// A count (of bytes, of slots) from an environment variable: the engine's knobs for tests and for
// runs that must leave memory to others.
#pragma once

#include <cstddef>

namespace deme {

// Whether `name` is set; if so its value, a whole number written in decimal digits only, goes to
// `out`, and anything else (empty, a sign, a unit) is a deme::Error from `call` naming the variable
// and saying it should be `what` ("a number of bytes").
bool environmentCount(const char* name, const char* call, const char* what, size_t& out);

}  // namespace deme
