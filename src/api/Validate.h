// Input checks shared by the API classes; each throws deme::Error naming the call.
#pragma once

#include <cmath>
#include <string>

#include <deme/Error.h>
#include <deme/VariableTypes.h>

namespace deme {

inline void requireFinite(const char* call, const char* what, double v) {
    if (!std::isfinite(v)) throwError(call, std::string(what) + " must be finite, got " + std::to_string(v));
}
inline void requirePositive(const char* call, const char* what, double v) {
    if (!(v > 0.0) || !std::isfinite(v))
        throwError(call, std::string(what) + " must be positive and finite, got " + std::to_string(v));
}
inline void requireFinite3(const char* call, const char* what, const float3& v) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throwError(call, std::string(what) + " must be finite");
}
inline void requirePositive3(const char* call, const char* what, const float3& v) {
    if (!(v.x > 0.f && v.y > 0.f && v.z > 0.f) || !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throwError(call, std::string(what) + " must have positive, finite components, got (" + std::to_string(v.x) +
                             ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")");
}
inline float3 requireUnitDirection(const char* call, const char* what, const float3& v) {
    requireFinite3(call, what, v);
    const float l = length(v);
    if (!(l > 0.f)) throwError(call, std::string(what) + " must not be the zero vector");
    return v / l;
}
// A box region [lo, hi]: finite, with hi > lo along every axis.
inline void requireBox(const char* call, const char* what, const float3& lo, const float3& hi) {
    const float l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
    for (int a = 0; a < 3; a++)
        if (!std::isfinite(l[a]) || !std::isfinite(h[a]) || !(h[a] > l[a]))
            throwError(call, std::string(what) + " needs finite bounds with hi > lo along each axis");
}
inline family_t requireFamily(const char* call, unsigned int family) {
    if (family >= NUM_FAMILIES)
        throwError(call,
                   "family " + std::to_string(family) + " is out of range 0.." + std::to_string(NUM_FAMILIES - 1));
    return (family_t)family;
}
inline float4 requireQuaternion(const char* call, const float4& q) {
    const float n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!(n > 0.f) || !std::isfinite(n)) throwError(call, "quaternion must be finite and non-zero");
    return make_float4(q.x / n, q.y / n, q.z / n, q.w / n);
}

}  // namespace deme
