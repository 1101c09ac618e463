// The engine's data types in one place (the paper's VariableTypes.h, §2.3). Change a typedef here
// and rebuild to trade range or precision for memory.
#pragma once

#include "HostDevice.h"  // the fixed-width integers, also under NVRTC
#include "VectorTypes.h"

namespace deme {

typedef uint8_t family_t;        // family tag of an owner, 0..255
typedef uint8_t materialID_t;    // material of a geometry
typedef uint32_t bodyID_t;       // owner id and geometry id
typedef uint32_t contactID_t;    // index into the active-contact set
typedef uint64_t voxelID_t;      // packed voxel index of a position
typedef uint16_t subVoxelPos_t;  // position inside a voxel, 2^16 steps per axis
typedef uint32_t inertiaID_t;    // index of an owner's mass properties
typedef float4 oriQ_t;           // owner orientation quaternion (w = scalar part)

// Bits of the packed voxel index given to each axis: 3 x 21 = 63 bits of a voxelID_t.
constexpr int VOXEL_BITS_PER_AXIS = 21;
constexpr int SUBVOXEL_BITS = 16;
constexpr double SUBVOXEL_STEPS = 65536.0;  // 2^SUBVOXEL_BITS

constexpr unsigned int NUM_FAMILIES = 256;
constexpr unsigned int MAX_MATERIALS = 256;
constexpr double PI = 3.14159265358979323846;

// What kind of geometry a contact's B side is; the A side is always a sphere.
enum ContactType : uint8_t { SPHERE_SPHERE = 0, SPHERE_ANALYTICAL = 1, SPHERE_TRIANGLE = 2 };

// Kinds of analytical components.
enum AnalyticalType : uint8_t { ANAL_PLANE = 0, ANAL_CYLINDER = 1 };

// What an owner is.
enum OwnerType : uint8_t { OWNER_CLUMP = 0, OWNER_ANALYTICAL = 1, OWNER_MESH = 2 };

}  // namespace deme
