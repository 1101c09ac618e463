// The paper's compact position (§2.3): a uint64 voxel index (21 bits per axis) plus three uint16
// offsets that split each voxel into 2^16 steps. For a 1 m domain one step is 1/2^37 m ~ 7e-12 m.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

struct DomainFrame {
    double3 origin;    // lower corner of the domain
    double voxelSize;  // edge of one voxel
    double subStep;    // voxelSize / 2^16: the position resolution
};

DEME_HD inline voxelID_t packVoxel(uint64_t vx, uint64_t vy, uint64_t vz) {
    return vx | (vy << VOXEL_BITS_PER_AXIS) | (vz << (2 * VOXEL_BITS_PER_AXIS));
}

DEME_HD inline void unpackVoxel(voxelID_t v, uint64_t& vx, uint64_t& vy, uint64_t& vz) {
    const uint64_t mask = (uint64_t(1) << VOXEL_BITS_PER_AXIS) - 1;
    vx = v & mask;
    vy = (v >> VOXEL_BITS_PER_AXIS) & mask;
    vz = (v >> (2 * VOXEL_BITS_PER_AXIS)) & mask;
}

// Largest representable integer coordinate along an axis (voxel and sub-voxel bits together).
constexpr int64_t MAX_GRID_COORD = (int64_t(1) << (VOXEL_BITS_PER_AXIS + SUBVOXEL_BITS)) - 1;

DEME_HD inline double decodeAxis(uint64_t voxel, subVoxelPos_t sub, double origin, double subStep) {
    return origin + (double)((int64_t)(voxel << SUBVOXEL_BITS) + (int64_t)sub) * subStep;
}

DEME_HD inline double3 decodePosition(voxelID_t voxel, subVoxelPos_t sx, subVoxelPos_t sy, subVoxelPos_t sz,
                                      const DomainFrame& f) {
    uint64_t vx, vy, vz;
    unpackVoxel(voxel, vx, vy, vz);
    return make_double3(decodeAxis(vx, sx, f.origin.x, f.subStep), decodeAxis(vy, sy, f.origin.y, f.subStep),
                        decodeAxis(vz, sz, f.origin.z, f.subStep));
}

// Rounds to the nearest representable position. Returns false (and leaves outputs untouched) if the
// position lies outside the representable range: the caller reports the owner as out of the domain.
DEME_HD inline bool encodePosition(const double3& p, const DomainFrame& f, voxelID_t& voxel, subVoxelPos_t& sx,
                                   subVoxelPos_t& sy, subVoxelPos_t& sz) {
    const double inv = 1.0 / f.subStep;
    const double gx = (p.x - f.origin.x) * inv + 0.5;
    const double gy = (p.y - f.origin.y) * inv + 0.5;
    const double gz = (p.z - f.origin.z) * inv + 0.5;
    // The negated comparisons also reject NaN.
    if (!(gx >= 0.0 && gy >= 0.0 && gz >= 0.0)) return false;
    if (!(gx <= (double)MAX_GRID_COORD && gy <= (double)MAX_GRID_COORD && gz <= (double)MAX_GRID_COORD)) return false;
    const int64_t ix = (int64_t)gx, iy = (int64_t)gy, iz = (int64_t)gz;
    voxel = packVoxel((uint64_t)ix >> SUBVOXEL_BITS, (uint64_t)iy >> SUBVOXEL_BITS, (uint64_t)iz >> SUBVOXEL_BITS);
    sx = (subVoxelPos_t)(ix & 0xFFFF);
    sy = (subVoxelPos_t)(iy & 0xFFFF);
    sz = (subVoxelPos_t)(iz & 0xFFFF);
    return true;
}

}  // namespace deme
