// DEMTracker's batch forms: all owners of a tracker read or set in one pass over the state, so that
// a batch of a million clumps costs one sweep instead of a million calls (each of which would look
// the state up again, and for setters refresh the contact set again).
#include <deme/Tracker.h>

#include <cmath>
#include <cstddef>
#include <string>

#include "api/Validate.h"
#include "physics/Quaternion.h"
#include "runtime/SceneEdits.h"
#include "runtime/Simulation.h"
#include "state/OwnerCentre.h"

namespace deme {

namespace {

// out[i] = value(internal id of offset i), for every owner of the tracker. Owners are stored in a
// space-filling-curve order, users see them in the order they added them: each row is looked up.
// One thread: a million rows take about 2 ms (bench/tracker_batch.py), and waking the OpenMP team
// for them measured slower on a busy 2-core machine (8 ms), not faster.
template <class T, class F>
void gather(const SimState& s, size_t first, size_t count, T* out, F value) {
    const bodyID_t* toInternal = s.ownerUserToInternal.data() + first;
    for (size_t i = 0; i < count; i++) out[i] = value((size_t)toInternal[i]);
}

// The internal ids of user ids [first, first + count).
std::vector<bodyID_t> internalRows(const SimState& s, size_t first, size_t count) {
    const auto from = s.ownerUserToInternal.begin() + (std::ptrdiff_t)first;
    return std::vector<bodyID_t>(from, from + (std::ptrdiff_t)count);
}

bool allFinite(const float3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string rowText(size_t i, const float3& v) {
    return "row " + std::to_string(i) + " (" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " +
           std::to_string(v.z) + ")";
}

}  // namespace

size_t DEMTracker::firstOwnerID(const char* call) const {
    if (!sim().initialized()) throwError(call, "the solver is not initialized yet");
    const size_t first = m_resolve();
    // Every row must be in the simulation: inserted (UpdateClumps) and not removed since.
    const SimState& s = sim().state();
    for (size_t i = 0; i < m_count; i++) liveOwner(s, first + i, call);
    return first;
}

void DEMTracker::Positions(float3* out) const {
    const size_t first = firstOwnerID("DEMTracker::Positions");
    const SimState& s = sim().state();
    gather(s, first, m_count, out, [&s](size_t o) { return to_float3(ownerCentre(s, o)); });
}
void DEMTracker::Velocities(float3* out) const {
    const size_t first = firstOwnerID("DEMTracker::Velocities");
    const SimState& s = sim().state();
    gather(s, first, m_count, out, [&s](size_t o) { return s.owners.vel[o]; });
}
void DEMTracker::AngularVelocities(float3* out) const {
    const size_t first = firstOwnerID("DEMTracker::AngularVelocities");
    const SimState& s = sim().state();
    gather(s, first, m_count, out, [&s](size_t o) { return rotateToGlobal(s.owners.oriQ[o], s.owners.angVel[o]); });
}
void DEMTracker::OriQs(float4* out) const {
    const size_t first = firstOwnerID("DEMTracker::OriQs");
    const SimState& s = sim().state();
    gather(s, first, m_count, out, [&s](size_t o) { return s.owners.oriQ[o]; });
}
// The rows' last-step loads come from Simulation::ownerLoads (on a GPU the device gathers them).
void DEMTracker::ContactForces(float3* out) const {
    const size_t first = firstOwnerID("DEMTracker::ContactForces");
    sim().ownerLoads(internalRows(sim().state(), first, m_count), out, nullptr);
}
void DEMTracker::ContactTorques(float3* out) const {
    const size_t first = firstOwnerID("DEMTracker::ContactTorques");
    sim().ownerLoads(internalRows(sim().state(), first, m_count), nullptr, out);
}

std::vector<float3> DEMTracker::Positions() const {
    std::vector<float3> v(m_count);
    Positions(v.data());
    return v;
}
std::vector<float3> DEMTracker::Velocities() const {
    std::vector<float3> v(m_count);
    Velocities(v.data());
    return v;
}
std::vector<float3> DEMTracker::AngularVelocities() const {
    std::vector<float3> v(m_count);
    AngularVelocities(v.data());
    return v;
}
std::vector<float4> DEMTracker::OriQs() const {
    std::vector<float4> v(m_count);
    OriQs(v.data());
    return v;
}
std::vector<float3> DEMTracker::ContactForces() const {
    std::vector<float3> v(m_count);
    ContactForces(v.data());
    return v;
}
std::vector<float3> DEMTracker::ContactTorques() const {
    std::vector<float3> v(m_count);
    ContactTorques(v.data());
    return v;
}

void DEMTracker::SetPositions(const float3* pos) {
    const char* call = "DEMTracker::SetPositions";
    const size_t first = firstOwnerID(call);
    // Encoded into scratch first: a row outside the domain throws before anything changed.
    const DomainFrame frame = sim().state().frame;
    std::vector<voxelID_t> voxel(m_count);
    std::vector<subVoxelPos_t> sub(3 * m_count);
    for (size_t i = 0; i < m_count; i++) {
        const float3 p = pos[i];
        if (!allFinite(p)) throwError(call, "position " + rowText(i, p) + " must be finite");
        if (!encodePosition(to_double3(p), frame, voxel[i], sub[3 * i], sub[3 * i + 1], sub[3 * i + 2]))
            throwError(call, "position " + rowText(i, p) + " is outside the simulation domain");
    }
    SimState& s = sim().editState();
    const bodyID_t* toInternal = s.ownerUserToInternal.data() + first;
    for (size_t i = 0; i < m_count; i++) {
        const size_t o = toInternal[i];
        s.owners.voxel[o] = voxel[i];
        s.owners.subX[o] = sub[3 * i];
        s.owners.subY[o] = sub[3 * i + 1];
        s.owners.subZ[o] = sub[3 * i + 2];
    }
    sim().invalidateContacts();
}

void DEMTracker::SetVelocities(const float3* vel) {
    const char* call = "DEMTracker::SetVelocities";
    const size_t first = firstOwnerID(call);
    for (size_t i = 0; i < m_count; i++)
        if (!allFinite(vel[i])) throwError(call, "velocity " + rowText(i, vel[i]) + " must be finite");
    SimState& s = sim().editState();
    const bodyID_t* toInternal = s.ownerUserToInternal.data() + first;
    for (size_t i = 0; i < m_count; i++) s.owners.vel[toInternal[i]] = vel[i];
    sim().invalidateContacts();
}

void DEMTracker::SetPositions(const std::vector<float3>& pos) {
    if (pos.size() != m_count)
        throwError("DEMTracker::SetPositions", "got " + std::to_string(pos.size()) + " positions for " +
                                                   std::to_string(m_count) + " owners");
    SetPositions(pos.data());
}
void DEMTracker::SetVelocities(const std::vector<float3>& vel) {
    if (vel.size() != m_count)
        throwError("DEMTracker::SetVelocities", "got " + std::to_string(vel.size()) + " velocities for " +
                                                    std::to_string(m_count) + " owners");
    SetVelocities(vel.data());
}

}  // namespace deme
