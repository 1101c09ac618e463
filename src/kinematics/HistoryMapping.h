// Contact history across re-detection (paper §3.2): a contact present before and after a detection
// keeps its wildcards; a new contact starts at zero.
#pragma once

#include "kinematics/ContactDetection.h"

namespace deme {

// Replaces s.contacts' pair list with `fresh` (sorted by key), carrying each surviving pair's
// wildcards over from the old list. Both lists are sorted, so each new pair finds its old self by
// binary search.
void installDetectedContacts(SimState& s, DetectedContacts& fresh);

}  // namespace deme
