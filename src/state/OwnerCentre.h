// Where an owner's centre is read. The state keeps an owner's position once, in the paper's compact
// form (§2.3: a voxel index and three sub-voxel offsets, 14 bytes), and every reader decodes it
// where it needs it, with the one expression the step itself uses (physics/CompactPosition.h), so
// every reader gets the same double, bit for bit. A cache of the decoded positions (24 bytes an
// owner, 29 % more than the compact form) was kept until 2026-12-07 (docs/memory.md). Plain code:
// NVRTC compiles it.
#pragma once

#include "physics/CompactPosition.h"

namespace deme {

// The voxel code of a clump parked by the "remove" exit policy (dynamics/OwnerStep.h): a code no
// position has (a position's code is 3 x 21 bits), which places clump o on the parking line.
constexpr voxelID_t PARKED_VOXEL = voxelID_t(1) << 63;

// The frame's parking line (DomainFrame::parking, made with the frame): parked clumps lie along the
// first bounded axis (an exit crosses a bounded face, so there is one), from 1000 domain lengths
// out, 4 domain lengths apart.
DEME_HD_INLINE ParkingLine parkingLine(const DomainFrame& f) {
    const unsigned int p = f.periodic.axes;
    const int a = !(p & 1u) ? 0 : !(p & 2u) ? 1 : 2;
    const double3 size = f.periodic.length;
    const double unit = fmax(size.x, fmax(size.y, size.z));
    const double3 axis = make_double3(a == 0 ? 1.0 : 0.0, a == 1 ? 1.0 : 0.0, a == 2 ? 1.0 : 0.0);
    return ParkingLine{f.origin + (1000.0 * unit) * axis, (4.0 * unit) * axis};
}

DEME_HD_INLINE double3 parkedPosition(const ParkingLine& line, size_t o) {
    return line.start + (double)o * line.stride;
}

// Owner o's centre, global frame, from its compact position (the frame's parking line for a parked
// clump, where the frame parks any). A select, not a branch: the CPU's force pass reads it in a
// vectorised loop.
DEME_HD_INLINE double3 ownerCentreOfCode(voxelID_t v, subVoxelPos_t sx, subVoxelPos_t sy, subVoxelPos_t sz,
                                         const DomainFrame& f, size_t o) {
    const double3 x = decodePosition(v, sx, sy, sz, f);
    return f.parks && (v & PARKED_VOXEL) ? parkedPosition(f.parking, o) : x;
}
// Whether spheres a and b, each its own owner, are farther apart than `reach` by their voxel codes
// alone: along each axis two centres whose voxels are d apart are more than (d - 1) voxels apart
// (a sub-voxel offset moves a centre by less than a voxel). One 8-byte load a sphere, where a
// decoded centre is four loads from four arrays: on a GPU the force pass turns a large set's apart
// pairs away with it before their centres are decoded (dynamics/ContactStep.h). Never true for a
// pair the exact test finds within reach (a millionth of the reach is left for rounding); not
// across a periodic face. A parked clump's code keeps its last voxel: the decoded centre, far
// away, settles a pair this passes.
template <class S>
DEME_HD_INLINE bool apartByVoxelCodes(const S& s, size_t a, size_t b, double reach) {
    uint64_t ax, ay, az, bx, by, bz;
    unpackVoxel(s.owners.voxel[a], ax, ay, az);
    unpackVoxel(s.owners.voxel[b], bx, by, bz);
    auto gap = [](uint64_t p, uint64_t q) {
        const uint64_t d = p > q ? p - q : q - p;
        return d > 1u ? (double)(d - 1u) : 0.0;
    };
    const double v = s.frame.voxelSize;
    const double3 g = make_double3(gap(ax, bx) * v, gap(ay, by) * v, gap(az, bz) * v);
    return dot(g, g) > reach * reach * (1.0 + 1e-6);
}

template <class S>
DEME_HD_INLINE double3 ownerCentre(const S& s, size_t o) {
    const auto& ow = s.owners;
    return ownerCentreOfCode(ow.voxel[o], ow.subX[o], ow.subY[o], ow.subZ[o], s.frame, o);
}

}  // namespace deme
