// The paper's compact position (§2.3): a uint64 voxel index (21 bits per axis) plus three uint16
// offsets that split each voxel into 2^16 steps. For a 1 m domain one step is 1/2^37 m ~ 7e-12 m.
#pragma once

#include <deme/VariableTypes.h>

#include "physics/Periodic.h"

namespace deme {

// Where clumps that left the domain under the "remove" exit policy wait for the host to take them
// out: clump o at start + o * stride (state/OwnerCentre.h).
struct ParkingLine {
    double3 start, stride;
};

struct DomainFrame {
    double3 origin;    // lower corner of the domain
    double voxelSize;  // edge of one voxel
    double subStep;    // voxelSize / 2^16: the position resolution
    PeriodicBox periodic{};  // the domain's edges and which axes are periodic (physics/Periodic.h)
    ParkingLine parking{};   // parkingLine(this frame), set with it: read wherever a centre is ...
    // ... where some clump may be parked: from the first call with the "remove" exit policy on
    // (Simulation::allowParking). Without it a centre is the decoded position alone: the select
    // costs the CPU's force pass some 3 % (BENCHMARKS.md, FORCE-PASS).
    bool parks = false;
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
// Written without branches (a candidate is always computed, then selected), so that the owner
// sweep that calls it vectorises.
DEME_HD inline bool encodePosition(const double3& p, const DomainFrame& f, voxelID_t& voxel, subVoxelPos_t& sx,
                                   subVoxelPos_t& sy, subVoxelPos_t& sz) {
    const double inv = 1.0 / f.subStep;
    const double g[3] = {(p.x - f.origin.x) * inv + 0.5, (p.y - f.origin.y) * inv + 0.5,
                         (p.z - f.origin.z) * inv + 0.5};
    // The negated comparisons also reject NaN.
    const bool ok = g[0] >= 0.0 && g[1] >= 0.0 && g[2] >= 0.0 && g[0] <= (double)MAX_GRID_COORD &&
                    g[1] <= (double)MAX_GRID_COORD && g[2] <= (double)MAX_GRID_COORD;
    int64_t i[3];
    for (int a = 0; a < 3; a++) i[a] = ok ? (int64_t)g[a] : 0;  // no out-of-range conversion
    const voxelID_t vNew =
        packVoxel((uint64_t)i[0] >> SUBVOXEL_BITS, (uint64_t)i[1] >> SUBVOXEL_BITS, (uint64_t)i[2] >> SUBVOXEL_BITS);
    voxel = ok ? vNew : voxel;
    sx = ok ? (subVoxelPos_t)(i[0] & 0xFFFF) : sx;
    sy = ok ? (subVoxelPos_t)(i[1] & 0xFFFF) : sy;
    sz = ok ? (subVoxelPos_t)(i[2] & 0xFFFF) : sz;
    return ok;
}

}  // namespace deme
