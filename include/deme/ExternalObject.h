// External objects: owners made of analytical components (planes, cylinders). They move only as
// their family or a tracker prescribes; contact forces on them are recorded for trackers.
#pragma once

#include <memory>
#include <vector>

#include "Materials.h"
#include "VariableTypes.h"

namespace deme {

class DEMExternObj {
  public:
    struct Component {
        AnalyticalType type;
        float3 pos;    // a point of the surface, object frame
        float3 dir;    // plane: unit normal towards the grains; cylinder: unit axis
        float radius;  // cylinder only
        bool inside;   // cylinder only: grains inside
        std::shared_ptr<DEMMaterial> material;
    };

    // Plane through pos; grains live on the side the normal points to.
    void AddPlane(const float3& pos, const float3& normal, const std::shared_ptr<DEMMaterial>& mat);
    // Infinite cylinder. normal_dir 0: grains inside, 1: grains outside (the paper's convention).
    void AddCylinder(const float3& pos, const float3& axis, float radius, const std::shared_ptr<DEMMaterial>& mat,
                     unsigned int normal_dir = 0);
    void SetFamily(unsigned int family);
    void SetInitPos(const float3& pos);
    void SetInitQuat(const float4& q);
    // Mass and MOI reported to trackers and used by the force model's effective mass; by default
    // the object counts as immovable (very large mass).
    void SetMass(float mass);
    void SetMOI(const float3& moi);

    const std::vector<Component>& GetComponents() const { return m_components; }
    family_t GetFamily() const { return m_family; }
    float3 GetInitPos() const { return m_pos; }
    float4 GetInitQuat() const { return m_oriQ; }
    float GetMass() const { return m_mass; }
    float3 GetMOI() const { return m_moi; }
    size_t GetOwnerID() const { return m_ownerID; }

  private:
    friend class DEMSolver;
    void checkNotInitialized(const char* call) const;
    std::vector<Component> m_components;
    family_t m_family = 0;
    float3 m_pos = make_float3(0.f);
    float4 m_oriQ = make_float4(0.f, 0.f, 0.f, 1.f);
    float m_mass;
    float3 m_moi;
    size_t m_ownerID = 0;
    bool m_initialized = false;

  public:
    DEMExternObj();
};

}  // namespace deme
