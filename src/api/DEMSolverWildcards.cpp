// DEMSolver: the force model's owner, geometry and contact wildcards, and persistent contacts, read
// and set from the host (docs/force-models.md). Ids are in user order.
#include <deme/DEMSolver.h>

#include <cmath>

#include "api/Scene.h"
#include "api/Validate.h"
#include "api/WildcardLookup.h"
#include "runtime/ContactEdits.h"
#include "runtime/SceneEdits.h"
#include "runtime/Simulation.h"
#include "state/SphereIds.h"

namespace deme {

namespace {

void requireIdRange(const char* call, const char* what, size_t first, size_t count, size_t total) {
    if (first >= total || count > total - first)
        throwError(call, std::string(what) + " id " + std::to_string(first + (count > 0 ? count - 1 : 0)) +
                             " is out of range (there are " + std::to_string(total) + ")");
}

void requireFiniteValue(const char* call, float v) { requireFinite(call, "wildcard value", v); }

}  // namespace

// ---------------------------------------------------------------- owner wildcards
void DEMSolver::SetOwnerWildcardValue(const std::string& name, size_t ownerID, float value) {
    SetOwnerWildcardValue(name, ownerID, std::vector<float>{value});
}

void DEMSolver::SetOwnerWildcardValue(const std::string& name, size_t firstOwnerID, const std::vector<float>& values) {
    const char* call = "SetOwnerWildcardValue";
    requireInitialized(call);
    SimState& s = m_sim->editState();
    const unsigned int w = wildcardIndex(*m_sim, call, WildcardKind::OWNER, name);
    requireIdRange(call, "owner", firstOwnerID, values.size(), s.ownerUserToInternal.size());
    for (float v : values) requireFiniteValue(call, v);
    for (size_t k = 0; k < values.size(); k++) liveOwner(s, firstOwnerID + k, call);  // all checked first
    for (size_t k = 0; k < values.size(); k++) s.wildcards.owner[w][s.ownerUserToInternal[firstOwnerID + k]] = values[k];
}

void DEMSolver::SetFamilyOwnerWildcardValue(unsigned int family, const std::string& name, float value) {
    const char* call = "SetFamilyOwnerWildcardValue";
    const family_t f = requireFamily(call, family);
    requireFiniteValue(call, value);
    if (!m_sim->initialized()) {
        m_scene->familyOwnerWildcards.push_back({f, name, value});  // the name is checked by Initialize
        return;
    }
    SimState& s = m_sim->editState();
    const unsigned int w = wildcardIndex(*m_sim, call, WildcardKind::OWNER, name);
    for (size_t o = 0; o < s.owners.size(); o++)
        if (s.owners.family[o] == f) s.wildcards.owner[w][o] = value;
}

float DEMSolver::GetOwnerWildcardValue(const std::string& name, size_t ownerID) const {
    return GetOwnerWildcardValue(name, ownerID, 1)[0];
}

std::vector<float> DEMSolver::GetOwnerWildcardValue(const std::string& name, size_t firstOwnerID, size_t count) const {
    const char* call = "GetOwnerWildcardValue";
    requireInitialized(call);
    const SimState& s = m_sim->state();
    const unsigned int w = wildcardIndex(*m_sim, call, WildcardKind::OWNER, name);
    requireIdRange(call, "owner", firstOwnerID, count, s.ownerUserToInternal.size());
    std::vector<float> out(count);
    for (size_t k = 0; k < count; k++) out[k] = s.wildcards.owner[w][liveOwner(s, firstOwnerID + k, call)];
    return out;
}

// ---------------------------------------------------------------- geometry wildcards
namespace {

// Geometry wildcard access in the unified id space: `toGeometry` maps a user id of the kind to it.
template <class ToGeometry>
void setGeometry(Simulation& sim, const char* call, const char* what, const std::string& name, size_t first,
                 const std::vector<float>& values, size_t total, ToGeometry toGeometry) {
    const unsigned int w = wildcardIndex(sim, call, WildcardKind::GEOMETRY, name);
    requireIdRange(call, what, first, values.size(), total);
    for (float v : values) requireFiniteValue(call, v);
    for (size_t k = 0; k < values.size(); k++) toGeometry(first + k);  // every id checked before any is set
    for (size_t k = 0; k < values.size(); k++) sim.editState().wildcards.geometry[w][toGeometry(first + k)] = values[k];
}

template <class ToGeometry>
std::vector<float> getGeometry(const Simulation& sim, const char* call, const char* what, const std::string& name,
                               size_t first, size_t count, size_t total, ToGeometry toGeometry) {
    const unsigned int w = wildcardIndex(sim, call, WildcardKind::GEOMETRY, name);
    requireIdRange(call, what, first, count, total);
    std::vector<float> out(count);
    for (size_t k = 0; k < count; k++) out[k] = sim.state().wildcards.geometry[w][toGeometry(first + k)];
    return out;
}

}  // namespace

void DEMSolver::SetSphereWildcardValue(const std::string& name, size_t sphereID, float value) {
    SetSphereWildcardValue(name, sphereID, std::vector<float>{value});
}

void DEMSolver::SetSphereWildcardValue(const std::string& name, size_t firstSphereID,
                                       const std::vector<float>& values) {
    const char* call = "SetSphereWildcardValue";
    requireInitialized(call);
    const SimState& s = m_sim->state();
    setGeometry(*m_sim, call, "sphere", name, firstSphereID, values, userSphereCount(s),
                [&](size_t u) { return liveSphere(s, u, call); });
}

float DEMSolver::GetSphereWildcardValue(const std::string& name, size_t sphereID) const {
    return GetSphereWildcardValue(name, sphereID, 1)[0];
}

std::vector<float> DEMSolver::GetSphereWildcardValue(const std::string& name, size_t firstSphereID,
                                                     size_t count) const {
    const char* call = "GetSphereWildcardValue";
    requireInitialized(call);
    const SimState& s = m_sim->state();
    return getGeometry(*m_sim, call, "sphere", name, firstSphereID, count, userSphereCount(s),
                       [&](size_t u) { return liveSphere(s, u, call); });
}

void DEMSolver::SetTriWildcardValue(const std::string& name, size_t triangleID, float value) {
    const char* call = "SetTriWildcardValue";
    requireInitialized(call);
    const SimState& s = m_sim->state();
    setGeometry(*m_sim, call, "triangle", name, triangleID, {value}, s.triangles.size(),
                [&](size_t t) { return s.triangleIdBase() + t; });
}

float DEMSolver::GetTriWildcardValue(const std::string& name, size_t triangleID) const {
    const char* call = "GetTriWildcardValue";
    requireInitialized(call);
    const SimState& s = m_sim->state();
    return getGeometry(*m_sim, call, "triangle", name, triangleID, 1, s.triangles.size(),
                       [&](size_t t) { return s.triangleIdBase() + t; })[0];
}

void DEMSolver::SetAnalWildcardValue(const std::string& name, size_t componentID, float value) {
    const char* call = "SetAnalWildcardValue";
    requireInitialized(call);
    const SimState& s = m_sim->state();
    setGeometry(*m_sim, call, "analytical component", name, componentID, {value}, s.analytical.size(),
                [&](size_t j) { return s.analyticalIdBase() + j; });
}

float DEMSolver::GetAnalWildcardValue(const std::string& name, size_t componentID) const {
    const char* call = "GetAnalWildcardValue";
    requireInitialized(call);
    const SimState& s = m_sim->state();
    return getGeometry(*m_sim, call, "analytical component", name, componentID, 1, s.analytical.size(),
                       [&](size_t j) { return s.analyticalIdBase() + j; })[0];
}

// ---------------------------------------------------------------- contact wildcards
namespace {

void setContactWildcards(Simulation& sim, const char* call, const FamilySelector& which, const std::string& name,
                         float value) {
    if (!sim.initialized())
        throwError(call,
                   "must be called after Initialize() (it changes the contacts now in "
                   "the set; for contacts to come, use SetFamilyContactWildcardInitValue)");
    const unsigned int w = wildcardIndex(sim, call, WildcardKind::CONTACT, name);
    requireFiniteValue(call, value);
    sim.refreshContactSet();
    setContactWildcard(sim.editStateWithContacts(), which, w, value);
}

}  // namespace

void DEMSolver::SetContactWildcardValue(const std::string& name, float value) {
    setContactWildcards(*m_sim, "SetContactWildcardValue", FamilySelector{}, name, value);
}

void DEMSolver::SetFamilyContactWildcardValue(unsigned int a, unsigned int b, const std::string& name, float value) {
    const char* call = "SetFamilyContactWildcardValue";
    setContactWildcards(*m_sim, call, {FamilySelector::Kind::PAIR, requireFamily(call, a), requireFamily(call, b)},
                        name, value);
}

void DEMSolver::SetFamilyContactWildcardValueEither(unsigned int family, const std::string& name, float value) {
    const char* call = "SetFamilyContactWildcardValueEither";
    setContactWildcards(*m_sim, call, {FamilySelector::Kind::EITHER, requireFamily(call, family), 0}, name, value);
}

void DEMSolver::SetFamilyContactWildcardValueBoth(unsigned int family, const std::string& name, float value) {
    const char* call = "SetFamilyContactWildcardValueBoth";
    setContactWildcards(*m_sim, call, {FamilySelector::Kind::BOTH, requireFamily(call, family), 0}, name, value);
}

void DEMSolver::SetFamilyContactWildcardInitValue(unsigned int a, unsigned int b, const std::string& name,
                                                  float value) {
    const char* call = "SetFamilyContactWildcardInitValue";
    const family_t fa = requireFamily(call, a), fb = requireFamily(call, b);
    requireFiniteValue(call, value);
    if (!m_sim->initialized()) {
        m_scene->contactWildcardInits.push_back({fa, fb, name, value});  // the name is checked by Initialize
        return;
    }
    addContactWildcardInit(m_sim->editState().wildcards,
                           {fa, fb, wildcardIndex(*m_sim, call, WildcardKind::CONTACT, name), value});
}

void DEMSolver::EnableOwnerWildcardOutput(bool enable) { m_sim->settings.outOwnerWildcards = enable; }

// ---------------------------------------------------------------- persistent contacts
namespace {

void setPersistence(Simulation& sim, const char* call, const FamilySelector& which, bool persistent) {
    if (!sim.initialized())
        throwError(call,
                   "must be called after Initialize() (it applies to the contacts now "
                   "in the set)");
    sim.refreshContactSet();
    setContactPersistence(sim.editStateWithContacts(), which, persistent);
}

}  // namespace

void DEMSolver::MarkPersistentContact() { setPersistence(*m_sim, "MarkPersistentContact", FamilySelector{}, true); }

void DEMSolver::MarkFamilyPersistentContact(unsigned int a, unsigned int b) {
    const char* call = "MarkFamilyPersistentContact";
    setPersistence(*m_sim, call, {FamilySelector::Kind::PAIR, requireFamily(call, a), requireFamily(call, b)}, true);
}

void DEMSolver::MarkFamilyPersistentContactEither(unsigned int family) {
    const char* call = "MarkFamilyPersistentContactEither";
    setPersistence(*m_sim, call, {FamilySelector::Kind::EITHER, requireFamily(call, family), 0}, true);
}

void DEMSolver::MarkFamilyPersistentContactBoth(unsigned int family) {
    const char* call = "MarkFamilyPersistentContactBoth";
    setPersistence(*m_sim, call, {FamilySelector::Kind::BOTH, requireFamily(call, family), 0}, true);
}

void DEMSolver::RemovePersistentContact() {
    setPersistence(*m_sim, "RemovePersistentContact", FamilySelector{}, false);
}

void DEMSolver::RemoveFamilyPersistentContact(unsigned int a, unsigned int b) {
    const char* call = "RemoveFamilyPersistentContact";
    setPersistence(*m_sim, call, {FamilySelector::Kind::PAIR, requireFamily(call, a), requireFamily(call, b)}, false);
}

void DEMSolver::RemoveFamilyPersistentContactEither(unsigned int family) {
    const char* call = "RemoveFamilyPersistentContactEither";
    setPersistence(*m_sim, call, {FamilySelector::Kind::EITHER, requireFamily(call, family), 0}, false);
}

void DEMSolver::RemoveFamilyPersistentContactBoth(unsigned int family) {
    const char* call = "RemoveFamilyPersistentContactBoth";
    setPersistence(*m_sim, call, {FamilySelector::Kind::BOTH, requireFamily(call, family), 0}, false);
}

size_t DEMSolver::GetNumPersistentContacts() const {
    return m_sim->initialized() ? countPersistentContacts(m_sim->stateWithContacts()) : 0;
}

}  // namespace deme
