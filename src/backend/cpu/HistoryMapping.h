// Contact history across re-detection (paper §3.2): a contact present before and after a detection
// keeps its wildcards; a new contact starts at zero (or at the value set for its families).
// Persistent contacts stay in the set even when detection no longer finds them.
#pragma once

#include "backend/cpu/ContactDetector.h"

namespace deme {

// Replaces s.contacts' pair list with `fresh` (sorted by key) plus the persistent pairs of the old
// list that `fresh` lacks, carrying each surviving pair's wildcards and persistence over. Both lists
// are sorted, so each new pair finds its old self by binary search, and the merge keeps the order.
// The new set has persistent flags where the old one had a persistent pair or the force model may
// set one (modelWritesPersistent: a custom model), and none otherwise (ContactArrays::persistent).
void installDetectedContacts(SimState& s, DetectedContacts& fresh, bool modelWritesPersistent);

// The set's persistent flags only where they are used (docs/memory.md): let go where no pair has
// one and the force model sets none, made (all 0) where the model may set one and there are none.
// Without flags every pair's is 0; CpuDynamics::downloadContacts makes them for host readers.
void keepPersistentFlagsWhereUsed(ContactArrays& c, bool modelWritesPersistent);

// The per-set bookkeeping of s.contacts' pairs as they are (the sphere-triangle runs, the force
// reduction's index and windows; ContactArrays::resetIndex empties it): part of every
// installation, of a restart that resumes a set, and of a step that finds it missing.
void indexContactSet(SimState& s);

}  // namespace deme
