// A detection's result made from a list of (A, B) pairs, for the tests of history mapping alone.
#pragma once

#include <utility>
#include <vector>

#include "backend/cpu/ContactDetector.h"

namespace deme_test {

inline deme::DetectedContacts detected(const std::vector<std::pair<deme::bodyID_t, deme::bodyID_t>>& pairs) {
    deme::DetectedContacts d;
    for (const auto& p : pairs) d.geomA.push_back(p.first), d.geomB.push_back(p.second);
    return d;
}

}  // namespace deme_test
