// DEMSolver: family changes of single owners on a condition (ChangeFamilyWhen), and the tracker's
// per-owner family setters. docs/active-box.md describes how they make an active box.
#include <deme/DEMSolver.h>
#include <deme/Tracker.h>

#include "api/Validate.h"
#include "codegen/FamilyCondition.h"
#include "runtime/Simulation.h"

namespace deme {

void DEMSolver::ChangeFamilyWhen(unsigned int from, unsigned int to, const std::string& condition) {
    const char* call = "ChangeFamilyWhen";
    FamilyCondition c;
    c.from = requireFamily(call, from);
    c.to = requireFamily(call, to);
    c.when = Expression::parseCondition(condition, familyConditionVariables(), call);
    m_sim->families.conditions().push_back(std::move(c));
}

void DEMSolver::ClearFamilyChangeConditions() { m_sim->families.conditions().clear(); }

void DEMTracker::SetFamily(unsigned int family, size_t offset) {
    const family_t f = requireFamily("DEMTracker::SetFamily", family);
    const size_t o = internalID(offset);
    sim().editState().owners.family[o] = f;
    sim().invalidateContacts();
}

void DEMTracker::SetFamilies(const unsigned int* families) {
    const char* call = "DEMTracker::SetFamilies";
    const size_t first = firstOwnerID(call);
    for (size_t i = 0; i < m_count; i++) requireFamily(call, families[i]);  // all checked before any is set
    SimState& s = sim().editState();
    const bodyID_t* toInternal = s.ownerUserToInternal.data() + first;
    for (size_t i = 0; i < m_count; i++) s.owners.family[toInternal[i]] = (family_t)families[i];
    sim().invalidateContacts();
}

void DEMTracker::SetFamilies(const std::vector<unsigned int>& families) {
    if (families.size() != m_count)
        throwError("DEMTracker::SetFamilies", "got " + std::to_string(families.size()) + " families for " +
                                                  std::to_string(m_count) + " owners");
    SetFamilies(families.data());
}

std::vector<unsigned int> DEMTracker::GetFamilies() const {
    const size_t first = firstOwnerID("DEMTracker::GetFamilies");
    const SimState& s = sim().state();
    std::vector<unsigned int> out(m_count);
    for (size_t i = 0; i < m_count; i++) out[i] = s.owners.family[s.ownerUserToInternal[first + i]];
    return out;
}

}  // namespace deme
