// Before a synchronous detection, the set in use keeps only the pairs that hand something to the
// next set (docs/memory.md, "A re-detection's peak"): the detection's peak holds the old set beside
// the bins and the new pairs, and in a flow detected with a wide margin most old pairs are apart,
// with nothing to hand over (kinematics/HistoryRules.h, pairCarriesHistory).
#pragma once

#include "state/SimState.h"

namespace deme {

// Drops the pairs of s.contacts that carry nothing to the next set, where that is most of them and
// no contact-init rule is set (new pairs would get its values, found ones not). Returns whether it
// dropped any: the set is then only the next installation's source, and serves no step (CpuDynamics
// detects afresh if that installation fails). Where the set keeps A as runs
// (backend/cpu/ContactARuns.h), its index must still be built: the kept pairs' A is made from the
// runs (restoring every pair's first was 4 B a pair at a detection's peak), and the set then holds
// geomA again; the caller empties the index after. DEME_KEEP_WHOLE_SET=1 keeps every pair (for
// comparisons).
bool keepOnlyCarriedPairs(SimState& s);

}  // namespace deme
