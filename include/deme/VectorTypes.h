// Small POD vector types used by the public API and by the single-source physics headers.
// No STL and no exceptions here: NVRTC compiles this file as it is.
//
// These are deme's own types, not CUDA's float3/float4 (which nvcc and NVRTC declare in the global
// namespace): inside namespace deme the names below hide CUDA's, and their layout is the same in
// host and device code (CUDA's float4 is 16-byte aligned, this one is not), so arrays built on the
// host are read unchanged on the device. Device code outside namespace deme names them deme::float3
// etc.; a `using namespace deme;` at global scope would make the unqualified names ambiguous there.
#pragma once

#include "HostDevice.h"

// NVRTC has no <cmath>; it predefines sqrt, sqrtf and the other math functions itself.
#if !defined(__CUDACC_RTC__)
#include <cmath>
#endif

namespace deme {

struct float3 {
    float x, y, z;
};
struct double3 {
    double x, y, z;
};
// Quaternions are stored as float4 with the scalar part in w: q = w + xi + yj + zk.
struct float4 {
    float x, y, z, w;
};

DEME_HD inline float3 make_float3(float x, float y, float z) { return float3{x, y, z}; }
DEME_HD inline float3 make_float3(float s) { return float3{s, s, s}; }
DEME_HD inline double3 make_double3(double x, double y, double z) { return double3{x, y, z}; }
DEME_HD inline float4 make_float4(float x, float y, float z, float w) { return float4{x, y, z, w}; }
DEME_HD inline float3 to_float3(const double3& a) { return float3{(float)a.x, (float)a.y, (float)a.z}; }
DEME_HD inline double3 to_double3(const float3& a) { return double3{a.x, a.y, a.z}; }

// ---- float3 arithmetic ----
DEME_HD inline float3 operator+(const float3& a, const float3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
DEME_HD inline float3 operator-(const float3& a, const float3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
DEME_HD inline float3 operator-(const float3& a) { return {-a.x, -a.y, -a.z}; }
DEME_HD inline float3 operator*(const float3& a, const float3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
DEME_HD inline float3 operator/(const float3& a, const float3& b) { return {a.x / b.x, a.y / b.y, a.z / b.z}; }
DEME_HD inline float3 operator*(const float3& a, float s) { return {a.x * s, a.y * s, a.z * s}; }
DEME_HD inline float3 operator*(float s, const float3& a) { return {a.x * s, a.y * s, a.z * s}; }
DEME_HD inline float3 operator/(const float3& a, float s) { return {a.x / s, a.y / s, a.z / s}; }
DEME_HD inline float3 operator+(const float3& a, float s) { return {a.x + s, a.y + s, a.z + s}; }
DEME_HD inline float3 operator-(const float3& a, float s) { return {a.x - s, a.y - s, a.z - s}; }
DEME_HD inline float3& operator+=(float3& a, const float3& b) {
    a.x += b.x;
    a.y += b.y;
    a.z += b.z;
    return a;
}
DEME_HD inline float3& operator-=(float3& a, const float3& b) {
    a.x -= b.x;
    a.y -= b.y;
    a.z -= b.z;
    return a;
}
DEME_HD inline float3& operator*=(float3& a, float s) {
    a.x *= s;
    a.y *= s;
    a.z *= s;
    return a;
}
DEME_HD inline float dot(const float3& a, const float3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
DEME_HD inline float3 cross(const float3& a, const float3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
DEME_HD inline float length(const float3& a) { return sqrtf(dot(a, a)); }
// Every component zero, of either sign.
DEME_HD inline bool isZero(const float3& a) { return a.x == 0.f && a.y == 0.f && a.z == 0.f; }

// ---- double3 arithmetic (positions and penetration are computed in double) ----
DEME_HD inline double3 operator+(const double3& a, const double3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
DEME_HD inline double3 operator-(const double3& a, const double3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
DEME_HD inline double3 operator-(const double3& a) { return {-a.x, -a.y, -a.z}; }
DEME_HD inline double3 operator*(const double3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
DEME_HD inline double3 operator*(double s, const double3& a) { return {a.x * s, a.y * s, a.z * s}; }
DEME_HD inline double3 operator/(const double3& a, double s) { return {a.x / s, a.y / s, a.z / s}; }
DEME_HD inline double3 operator+(const double3& a, const float3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
DEME_HD inline double3 operator-(const double3& a, const float3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
DEME_HD inline double3& operator+=(double3& a, const double3& b) {
    a.x += b.x;
    a.y += b.y;
    a.z += b.z;
    return a;
}
DEME_HD inline double dot(const double3& a, const double3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
DEME_HD inline double3 cross(const double3& a, const double3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
DEME_HD inline double length(const double3& a) { return sqrt(dot(a, a)); }

}  // namespace deme
