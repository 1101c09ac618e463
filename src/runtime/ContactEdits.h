// Host-side edits of the active-contact set between steps (DEMSolver::MarkPersistentContact,
// SetFamilyContactWildcardValue, ...): which contacts an edit applies to, chosen by the families of
// their two owners, and the edits themselves.
#pragma once

#include "state/SimState.h"

namespace deme {

struct FamilySelector {
    enum class Kind { ALL, EITHER, BOTH, PAIR } kind = Kind::ALL;
    family_t a = 0, b = 0;  // EITHER/BOTH: family a; PAIR: one owner in a, the other in b

    bool matches(family_t fa, family_t fb) const {
        switch (kind) {
            case Kind::EITHER:
                return fa == a || fb == a;
            case Kind::BOTH:
                return fa == a && fb == a;
            case Kind::PAIR:
                return (fa == a && fb == b) || (fa == b && fb == a);
            default:
                return true;
        }
    }
};

// Sets or clears the persistence of the selected contacts; returns how many were selected.
size_t setContactPersistence(SimState& s, const FamilySelector& which, bool persistent);

// Sets contact wildcard `index` of the selected contacts; returns how many were selected.
size_t setContactWildcard(SimState& s, const FamilySelector& which, unsigned int index, float value);

size_t countPersistentContacts(const SimState& s);

// Adds the rule that contacts entering the set between two families start with a value; it replaces
// an earlier rule for the same families (either order) and wildcard.
void addContactWildcardInit(WildcardArrays& w, const WildcardArrays::ContactInit& rule);

}  // namespace deme
