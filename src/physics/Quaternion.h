// Quaternion operations on float4 (w = scalar part). Orientation q maps local (body) vectors to global.
#pragma once

#include <deme/VectorTypes.h>

namespace deme {

// v_global = q * v_local * conj(q), computed in the expanded form (no temporaries).
DEME_HD inline float3 rotateToGlobal(const float4& q, const float3& v) {
    const float3 u = make_float3(q.x, q.y, q.z);
    const float3 t = 2.f * cross(u, v);
    return v + q.w * t + cross(u, t);
}

// v_local = conj(q) * v_global * q.
DEME_HD inline float3 rotateToLocal(const float4& q, const float3& v) {
    const float3 u = make_float3(-q.x, -q.y, -q.z);
    const float3 t = 2.f * cross(u, v);
    return v + q.w * t + cross(u, t);
}

// Double-precision rotation of a float offset; used where an offset is added to a double position.
DEME_HD inline double3 rotateToGlobal(const float4& q, const double3& v) {
    const double3 u = make_double3(q.x, q.y, q.z);
    const double3 t = 2.0 * cross(u, v);
    return v + (double)q.w * t + cross(u, t);
}

// The paper's helper: rotate (x, y, z) in place by the quaternion (w, qx, qy, qz).
DEME_HD inline void applyOriQToVector3(float& x, float& y, float& z, float w, float qx, float qy, float qz) {
    const float3 r = rotateToGlobal(make_float4(qx, qy, qz, w), make_float3(x, y, z));
    x = r.x;
    y = r.y;
    z = r.z;
}

DEME_HD inline float4 quatMultiply(const float4& a, const float4& b) {
    return make_float4(a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,  //
                       a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,  //
                       a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,  //
                       a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z);
}

// One division and four products: on a GPU a correctly rounded division of a zero (the components of
// an owner that has not turned about an axis) takes the division's slow path, one call per
// component in every owner step.
DEME_HD inline float4 quatNormalize(const float4& q) {
    const float inv = 1.f / sqrtf(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    return make_float4(q.x * inv, q.y * inv, q.z * inv, q.w * inv);
}

// Largest squared half angle per step for which orientationStepSeries is accurate to float
// rounding: at a half angle of 0.1 rad the first omitted Taylor terms are below 3e-13.
constexpr float ORIENTATION_SERIES_MAX_H2 = 0.01f;

// The exponential-map step below with sin and cos of the half angle by Taylor series, given the
// squared half angle h2 = (|w| dt / 2)^2 < ORIENTATION_SERIES_MAX_H2. Free of calls, so that loops
// over many owners vectorise.
DEME_HD inline float4 orientationStepSeries(const float4& q, const float3& omegaLocal, float dt, float h2) {
    const float sinc = 1.f - h2 * (1.f / 6.f - h2 * (1.f / 120.f - h2 * (1.f / 5040.f)));  // sin(half)/half
    const float c = 1.f - h2 * (0.5f - h2 * (1.f / 24.f - h2 * (1.f / 720.f)));           // cos(half)
    const float s = 0.5f * dt * sinc;                                                      // sin(half) / |w|
    const float4 dq = make_float4(omegaLocal.x * s, omegaLocal.y * s, omegaLocal.z * s, c);
    return quatNormalize(quatMultiply(q, dq));
}

// Advances q by a rotation of angle |w|*dt about the body-frame axis w (exact exponential map for
// constant w over the step, so a prescribed spin turns by exactly w*t), then renormalises.
DEME_HD inline float4 integrateOrientation(const float4& q, const float3& omegaLocal, float dt) {
    const float w2 = dot(omegaLocal, omegaLocal);
    if (!(w2 > 0.f)) return q;
    const float h2 = 0.25f * w2 * dt * dt;  // (half angle)^2
    if (h2 < ORIENTATION_SERIES_MAX_H2) return orientationStepSeries(q, omegaLocal, dt, h2);
    const float half = sqrtf(h2);
    const float s = 0.5f * dt * (sinf(half) / half);
    const float4 dq = make_float4(omegaLocal.x * s, omegaLocal.y * s, omegaLocal.z * s, cosf(half));
    return quatNormalize(quatMultiply(q, dq));
}

}  // namespace deme
