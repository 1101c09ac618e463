// Trackers: read and steer one owner, or each clump of a batch, while the simulation runs.
#pragma once

#include <functional>
#include <memory>
#include <string>

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

    size_t GetNumOwners() const { return m_count; }
    // The owner's id in user order: clumps in the order they were added, then external objects.
    size_t GetOwnerID(size_t offset = 0) const;

  private:
    size_t internalID(size_t offset) const;  // where the owner is stored
    Simulation& sim() const;                 // the solver's simulation; an error once the solver is gone
    std::weak_ptr<Simulation> m_owner;       // expired once the solver is destroyed
    Simulation* m_sim;
    std::function<size_t()> m_resolve;
    size_t m_count;
};

}  // namespace deme
