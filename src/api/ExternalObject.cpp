#include <deme/ExternalObject.h>

#include "api/Validate.h"
#include "physics/ContactGeometry.h"

namespace deme {

DEMExternObj::DEMExternObj() : m_mass(IMMOVABLE_MASS), m_moi(make_float3(IMMOVABLE_MASS)) {}

void DEMExternObj::checkNotInitialized(const char* call) const {
    if (m_initialized) throwError(call, "the object is already initialized; use a tracker to move it");
}

void DEMExternObj::AddPlane(const float3& pos, const float3& normal, const std::shared_ptr<DEMMaterial>& mat) {
    const char* call = "DEMExternObj::AddPlane";
    checkNotInitialized(call);
    requireFinite3(call, "position", pos);
    const float3 n = requireUnitDirection(call, "normal", normal);
    if (!mat) throwError(call, "material is null");
    m_components.push_back(Component{ANAL_PLANE, pos, n, 0.f, false, mat});
}

void DEMExternObj::AddCylinder(const float3& pos, const float3& axis, float radius,
                               const std::shared_ptr<DEMMaterial>& mat, unsigned int normal_dir) {
    const char* call = "DEMExternObj::AddCylinder";
    checkNotInitialized(call);
    requireFinite3(call, "position", pos);
    const float3 a = requireUnitDirection(call, "axis", axis);
    requirePositive(call, "radius", radius);
    if (normal_dir > 1) throwError(call, "normal_dir must be 0 (grains inside) or 1 (grains outside)");
    if (!mat) throwError(call, "material is null");
    m_components.push_back(Component{ANAL_CYLINDER, pos, a, radius, normal_dir == 0, mat});
}

void DEMExternObj::SetFamily(unsigned int family) {
    checkNotInitialized("DEMExternObj::SetFamily");
    m_family = requireFamily("DEMExternObj::SetFamily", family);
}
void DEMExternObj::SetInitPos(const float3& pos) {
    checkNotInitialized("DEMExternObj::SetInitPos");
    requireFinite3("DEMExternObj::SetInitPos", "position", pos);
    m_pos = pos;
}
void DEMExternObj::SetInitQuat(const float4& q) {
    checkNotInitialized("DEMExternObj::SetInitQuat");
    m_oriQ = requireQuaternion("DEMExternObj::SetInitQuat", q);
}
void DEMExternObj::SetMass(float mass) {
    checkNotInitialized("DEMExternObj::SetMass");
    requirePositive("DEMExternObj::SetMass", "mass", mass);
    m_mass = mass;
}
void DEMExternObj::SetMOI(const float3& moi) {
    checkNotInitialized("DEMExternObj::SetMOI");
    requirePositive3("DEMExternObj::SetMOI", "MOI", moi);
    m_moi = moi;
}

}  // namespace deme
