#include <deme/Tracker.h>

#include "api/Validate.h"
#include "api/WildcardLookup.h"
#include "physics/Quaternion.h"
#include "runtime/Simulation.h"

namespace deme {

DEMTracker::DEMTracker(Simulation* sim, std::function<size_t()> resolve, size_t count)
    : m_sim(sim), m_resolve(std::move(resolve)), m_count(count) {}

size_t DEMTracker::GetOwnerID(size_t offset) const {
    if (!m_sim->initialized()) throwError("DEMTracker", "the solver is not initialized yet");
    if (offset >= m_count)
        throwError("DEMTracker", "offset " + std::to_string(offset) + " is out of range (tracking " +
                                     std::to_string(m_count) + " owners)");
    return m_resolve() + offset;
}

size_t DEMTracker::internalID(size_t offset) const { return m_sim->state().ownerUserToInternal[GetOwnerID(offset)]; }

float3 DEMTracker::Pos(size_t offset) const { return to_float3(m_sim->ownerPos(internalID(offset))); }
float3 DEMTracker::Vel(size_t offset) const { return m_sim->state().owners.vel[internalID(offset)]; }
float3 DEMTracker::AngVelLocal(size_t offset) const { return m_sim->state().owners.angVel[internalID(offset)]; }
float3 DEMTracker::AngVelGlobal(size_t offset) const {
    const size_t o = internalID(offset);
    return rotateToGlobal(m_sim->state().owners.oriQ[o], m_sim->state().owners.angVel[o]);
}
float4 DEMTracker::OriQ(size_t offset) const { return m_sim->state().owners.oriQ[internalID(offset)]; }
float DEMTracker::Mass(size_t offset) const { return m_sim->ownerMass(internalID(offset)); }
float3 DEMTracker::MOI(size_t offset) const { return m_sim->ownerMOI(internalID(offset)); }
unsigned int DEMTracker::GetFamily(size_t offset) const { return m_sim->state().owners.family[internalID(offset)]; }
float3 DEMTracker::ContactForce(size_t offset) const { return m_sim->state().owners.contactForce[internalID(offset)]; }
float3 DEMTracker::ContactTorque(size_t offset) const {
    return m_sim->state().owners.contactTorque[internalID(offset)];
}
float3 DEMTracker::ContactAcc(size_t offset) const {
    const size_t o = internalID(offset);
    return m_sim->state().owners.contactForce[o] / m_sim->ownerMass(o);
}
float3 DEMTracker::ContactAngAccLocal(size_t offset) const {
    const size_t o = internalID(offset);
    const float3 tLocal = rotateToLocal(m_sim->state().owners.oriQ[o], m_sim->state().owners.contactTorque[o]);
    return tLocal / m_sim->ownerMOI(o);
}

void DEMTracker::SetPos(const float3& pos, size_t offset) {
    requireFinite3("DEMTracker::SetPos", "position", pos);
    m_sim->setOwnerPos(internalID(offset), to_double3(pos), "DEMTracker::SetPos");
}
void DEMTracker::SetVel(const float3& vel, size_t offset) {
    requireFinite3("DEMTracker::SetVel", "velocity", vel);
    m_sim->editState().owners.vel[internalID(offset)] = vel;
    m_sim->invalidateContacts();
}
void DEMTracker::SetAngVel(const float3& w, size_t offset) {
    requireFinite3("DEMTracker::SetAngVel", "angular velocity", w);
    m_sim->editState().owners.angVel[internalID(offset)] = w;
    m_sim->invalidateContacts();
}
void DEMTracker::SetOriQ(const float4& q, size_t offset) {
    m_sim->editState().owners.oriQ[internalID(offset)] = requireQuaternion("DEMTracker::SetOriQ", q);
    m_sim->invalidateContacts();
}
void DEMTracker::AddAcc(const float3& acc, size_t offset) {
    requireFinite3("DEMTracker::AddAcc", "acceleration", acc);
    m_sim->trackerLoadState().owners.extraAcc[internalID(offset)] += acc;
    m_sim->trackerLoadState().hasTrackerLoads = true;
}
void DEMTracker::AddAngAcc(const float3& angAcc, size_t offset) {
    requireFinite3("DEMTracker::AddAngAcc", "angular acceleration", angAcc);
    m_sim->trackerLoadState().owners.extraAngAcc[internalID(offset)] += angAcc;
    m_sim->trackerLoadState().hasTrackerLoads = true;
}

void DEMTracker::SetOwnerWildcardValue(const std::string& name, float value, size_t offset) {
    const char* call = "DEMTracker::SetOwnerWildcardValue";
    requireFinite(call, "wildcard value", value);
    const size_t o = internalID(offset);
    m_sim->editState().wildcards.owner[wildcardIndex(*m_sim, call, WildcardKind::OWNER, name)][o] = value;
}
float DEMTracker::GetOwnerWildcardValue(const std::string& name, size_t offset) const {
    const size_t o = internalID(offset);
    return m_sim->state()
        .wildcards.owner[wildcardIndex(*m_sim, "DEMTracker::GetOwnerWildcardValue", WildcardKind::OWNER, name)][o];
}

}  // namespace deme
