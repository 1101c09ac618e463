// The CPU's check of the family conditions (ChangeFamilyWhen): every owner, in parallel, through
// the per-owner rule of dynamics/FamilyChangeRule.h, with the conditions evaluated from their
// parsed form. The GPU runs the same rule in a generated kernel (codegen/FamilyConditionSource.cpp).
#include "backend/cpu/CpuDynamics.h"
#include "dynamics/FamilyChangeRule.h"
#include "parallel/Parallel.h"

namespace deme {

size_t CpuDynamics::applyFamilyConditions(double time, const FamilyRules& families) {
    const std::vector<FamilyCondition>& rules = families.conditions();
    const size_t n = m_s.owners.size();
    size_t changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed) if (n > PARALLEL_MIN_ITEMS)
    for (size_t o = 0; o < n; o++) {
        double v[FAMILY_CONDITION_VARS];
        bool haveInputs = false;
        for (const FamilyCondition& c : rules) {
            if (m_s.owners.family[o] != c.from) continue;  // most owners: no condition evaluated
            if (!haveInputs) familyConditionInputs(m_s, o, time, v);
            haveInputs = true;
            if (applyFamilyRule(m_s, o, c.from, c.to, c.when.evaluate(v))) {
                changed++;
                break;
            }
        }
    }
    if (changed) m_subsetStale = true;
    return changed;
}

}  // namespace deme
