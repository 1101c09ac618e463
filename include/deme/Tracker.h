// Trackers: read and steer one owner, or each clump of a batch, while the simulation runs.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "VariableTypes.h"

namespace deme {

class Simulation;

// All getters and setters take an offset selecting a clump within the tracked batch (0 for an
// external object). Values are global unless named Local. Valid after Initialize.
class DEMTracker {
  public:
    // `resolve` returns the first owner id of the tracked entity once the solver is initialised. A
    // tracker outliving its solver says so (deme::Error) instead of reading freed memory.
    DEMTracker(std::weak_ptr<Simulation> sim, std::function<size_t()> resolve, size_t count);

    float3 Pos(size_t offset = 0) const;
    float3 Vel(size_t offset = 0) const;
    float3 AngVelLocal(size_t offset = 0) const;
    float3 AngVelGlobal(size_t offset = 0) const;
    float4 OriQ(size_t offset = 0) const;
    float Mass(size_t offset = 0) const;
    float3 MOI(size_t offset = 0) const;
    unsigned int GetFamily(size_t offset = 0) const;
    // Contact force over mass, and contact torque over MOI in the local frame, from the last step.
    float3 ContactAcc(size_t offset = 0) const;
    float3 ContactAngAccLocal(size_t offset = 0) const;
    // Contact force and torque (global) from the last step.
    float3 ContactForce(size_t offset = 0) const;
    float3 ContactTorque(size_t offset = 0) const;

    void SetPos(const float3& pos, size_t offset = 0);
    void SetVel(const float3& vel, size_t offset = 0);
    void SetAngVel(const float3& angVelLocal, size_t offset = 0);
    void SetOriQ(const float4& q, size_t offset = 0);
    // Extra acceleration, applied on every step of the next DoDynamics/DoStepDynamics call.
    void AddAcc(const float3& acc, size_t offset = 0);
    void AddAngAcc(const float3& angAccLocal, size_t offset = 0);
    // The force model's owner wildcards (DEMForceModel::SetPerOwnerWildcards) of the tracked owner.
    void SetOwnerWildcardValue(const std::string& name, float value, size_t offset = 0);
    float GetOwnerWildcardValue(const std::string& name, size_t offset = 0) const;

    // ---- Batch forms: every owner of the tracker in one pass, in offset order (offset 0 first) ----
    // The pointer forms fill the caller's buffer of GetNumOwners() elements (a numpy array's memory,
    // for instance); the others return a new vector. On the GPU backend the state comes back from
    // the device once per call, not once per owner.
    void Positions(float3* out) const;
    void Velocities(float3* out) const;
    void AngularVelocities(float3* out) const;  // global frame, as AngVelGlobal
    void OriQs(float4* out) const;
    void ContactForces(float3* out) const;   // global, as ContactForce
    void ContactTorques(float3* out) const;  // global, as ContactTorque
    std::vector<float3> Positions() const;
    std::vector<float3> Velocities() const;
    std::vector<float3> AngularVelocities() const;
    std::vector<float4> OriQs() const;
    std::vector<float3> ContactForces() const;
    std::vector<float3> ContactTorques() const;
    // Set every owner at once from GetNumOwners() values. All values are checked before any is
    // applied, so a bad one (not finite, outside the domain) changes nothing; the contact set is
    // refreshed once, not once per owner as SetPos / SetVel in a loop would.
    void SetPositions(const float3* pos);
    void SetVelocities(const float3* vel);
    void SetPositions(const std::vector<float3>& pos);
    void SetVelocities(const std::vector<float3>& vel);

    // The family of one owner, or of every owner (GetNumOwners() values, all checked before any is
    // applied), between DoDynamics calls; the next step re-detects contacts (docs/active-box.md).
    void SetFamily(unsigned int family, size_t offset = 0);
    void SetFamilies(const unsigned int* families);
    void SetFamilies(const std::vector<unsigned int>& families);
    std::vector<unsigned int> GetFamilies() const;

    size_t GetNumOwners() const { return m_count; }
    // The owner's id in user order: clumps in the order they were added, then external objects.
    size_t GetOwnerID(size_t offset = 0) const;

  private:
    size_t internalID(size_t offset) const;  // where the owner is stored
    Simulation& sim() const;                 // the solver's simulation; an error once the solver is gone
    std::weak_ptr<Simulation> m_owner;       // expired once the solver is destroyed
    size_t firstOwnerID(const char* call) const;  // user id of offset 0; checks the solver is initialized
    Simulation* m_sim;
    std::function<size_t()> m_resolve;
    size_t m_count;
};

}  // namespace deme
