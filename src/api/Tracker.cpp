#include <deme/Tracker.h>

#include "api/Validate.h"
#include "api/WildcardLookup.h"
#include "physics/Quaternion.h"
#include "runtime/SceneEdits.h"
#include "runtime/Simulation.h"

namespace deme {

DEMTracker::DEMTracker(std::weak_ptr<Simulation> sim, std::function<size_t()> resolve, size_t count)
    : m_owner(std::move(sim)), m_sim(m_owner.lock().get()), m_resolve(std::move(resolve)), m_count(count) {}

Simulation& DEMTracker::sim() const {
    if (m_owner.expired()) throwError("DEMTracker", "the solver this tracker belongs to has been destroyed");
    return *m_sim;
}

size_t DEMTracker::GetOwnerID(size_t offset) const {
    if (!sim().initialized()) throwError("DEMTracker", "the solver is not initialized yet");
    if (offset >= m_count)
        throwError("DEMTracker", "offset " + std::to_string(offset) + " is out of range (tracking " +
                                     std::to_string(m_count) + " owners)");
    return m_resolve() + offset;
}

size_t DEMTracker::internalID(size_t offset) const { return liveOwner(sim().state(), GetOwnerID(offset), "DEMTracker"); }

float3 DEMTracker::Pos(size_t offset) const { return to_float3(sim().ownerPos(internalID(offset))); }
float3 DEMTracker::Vel(size_t offset) const { return sim().state().owners.vel[internalID(offset)]; }
float3 DEMTracker::AngVelLocal(size_t offset) const { return sim().state().owners.angVel[internalID(offset)]; }
float3 DEMTracker::AngVelGlobal(size_t offset) const {
    const size_t o = internalID(offset);
    return rotateToGlobal(sim().state().owners.oriQ[o], sim().state().owners.angVel[o]);
}
float4 DEMTracker::OriQ(size_t offset) const { return sim().state().owners.oriQ[internalID(offset)]; }
float DEMTracker::Mass(size_t offset) const { return sim().ownerMass(internalID(offset)); }
float3 DEMTracker::MOI(size_t offset) const { return sim().ownerMOI(internalID(offset)); }
unsigned int DEMTracker::GetFamily(size_t offset) const { return sim().state().owners.family[internalID(offset)]; }
namespace {

// Owner o's last-step contact force and torque (Simulation::ownerLoads: the device's, on a GPU).
struct Loads {
    float3 force, torque;
};
Loads loadsOf(const Simulation& sim, size_t o) {
    Loads l;
    sim.ownerLoads({(bodyID_t)o}, &l.force, &l.torque);
    return l;
}

}  // namespace

float3 DEMTracker::ContactForce(size_t offset) const { return loadsOf(sim(), internalID(offset)).force; }
float3 DEMTracker::ContactTorque(size_t offset) const { return loadsOf(sim(), internalID(offset)).torque; }
float3 DEMTracker::ContactAcc(size_t offset) const {
    const size_t o = internalID(offset);
    return loadsOf(sim(), o).force / sim().ownerMass(o);
}
float3 DEMTracker::ContactAngAccLocal(size_t offset) const {
    const size_t o = internalID(offset);
    const float3 tLocal = rotateToLocal(sim().state().owners.oriQ[o], loadsOf(sim(), o).torque);
    return tLocal / sim().ownerMOI(o);
}

void DEMTracker::SetPos(const float3& pos, size_t offset) {
    requireFinite3("DEMTracker::SetPos", "position", pos);
    sim().setOwnerPos(internalID(offset), to_double3(pos), "DEMTracker::SetPos");
}
void DEMTracker::SetVel(const float3& vel, size_t offset) {
    requireFinite3("DEMTracker::SetVel", "velocity", vel);
    sim().editState().owners.vel[internalID(offset)] = vel;
    sim().invalidateContacts();
}
void DEMTracker::SetAngVel(const float3& w, size_t offset) {
    requireFinite3("DEMTracker::SetAngVel", "angular velocity", w);
    sim().editState().owners.angVel[internalID(offset)] = w;
    sim().invalidateContacts();
}
void DEMTracker::SetOriQ(const float4& q, size_t offset) {
    sim().editState().owners.oriQ[internalID(offset)] = requireQuaternion("DEMTracker::SetOriQ", q);
    sim().invalidateContacts();
}
void DEMTracker::AddAcc(const float3& acc, size_t offset) {
    requireFinite3("DEMTracker::AddAcc", "acceleration", acc);
    const size_t o = internalID(offset);
    sim().trackerLoads().extraAcc[o] += acc;
}
void DEMTracker::AddAngAcc(const float3& angAcc, size_t offset) {
    requireFinite3("DEMTracker::AddAngAcc", "angular acceleration", angAcc);
    const size_t o = internalID(offset);
    sim().trackerLoads().extraAngAcc[o] += angAcc;
}

void DEMTracker::SetOwnerWildcardValue(const std::string& name, float value, size_t offset) {
    const char* call = "DEMTracker::SetOwnerWildcardValue";
    requireFinite(call, "wildcard value", value);
    const size_t o = internalID(offset);
    sim().editState().wildcards.owner[wildcardIndex(sim(), call, WildcardKind::OWNER, name)][o] = value;
}
float DEMTracker::GetOwnerWildcardValue(const std::string& name, size_t offset) const {
    const size_t o = internalID(offset);
    return sim()
        .state()
        .wildcards.owner[wildcardIndex(sim(), "DEMTracker::GetOwnerWildcardValue", WildcardKind::OWNER, name)][o];
}

}  // namespace deme
