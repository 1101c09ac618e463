// Contact geometry between a sphere (always side A) and the other geometry (side B). Each function
// returns the overlap depth in double (negative: the surfaces are apart by that much), the unit
// normal B2A pointing from B to A, and the contact point: the middle of the overlap along the normal.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

// Curvature radius reported for flat analytical surfaces, and the mass reported for owners that the
// contacts cannot move. Large but finite so that products like mA*mB stay inside float range.
constexpr float FLAT_SURFACE_RADIUS = 1e10f;
constexpr float IMMOVABLE_MASS = 1e10f;

struct ContactPoint {
    double overlap;
    float3 B2A;
    double3 point;
};

DEME_HD inline ContactPoint sphereSphereContact(const double3& posA, double rA, const double3& posB, double rB) {
    ContactPoint c;
    const double3 d = posA - posB;
    const double dist = length(d);
    c.overlap = rA + rB - dist;
    // Coincident centres have no defined normal; any unit vector keeps the force finite.
    const double3 n = dist > 0.0 ? d / dist : make_double3(0.0, 0.0, 1.0);
    c.B2A = to_float3(n);
    c.point = posB + n * (rB - 0.5 * c.overlap);
    return c;
}

// Plane through `planePoint` with unit normal `normal` pointing to the side where grains live.
DEME_HD inline ContactPoint spherePlaneContact(const double3& posA, double rA, const double3& planePoint,
                                               const double3& normal) {
    ContactPoint c;
    const double dist = dot(posA - planePoint, normal);
    c.overlap = rA - dist;
    c.B2A = to_float3(normal);
    c.point = posA - normal * (rA - 0.5 * c.overlap);
    return c;
}

// Infinite cylinder with axis through `axisPoint` along unit `axis`, radius R. `grainsInside`
// selects the side the grains live on (the paper's last AddCylinder argument: 0 inside, 1 outside).
DEME_HD inline ContactPoint sphereCylinderContact(const double3& posA, double rA, const double3& axisPoint,
                                                  const double3& axis, double R, bool grainsInside) {
    ContactPoint c;
    const double3 rel = posA - axisPoint;
    const double3 radial = rel - axis * dot(rel, axis);
    const double rho = length(radial);
    // On the axis the radial direction is undefined; pick one perpendicular to the axis.
    double3 u;
    if (rho > 0.0) {
        u = radial / rho;
    } else {
        const double3 t = fabs(axis.x) < 0.9 ? make_double3(1.0, 0.0, 0.0) : make_double3(0.0, 1.0, 0.0);
        const double3 p = cross(axis, t);
        u = p / length(p);
    }
    const double dist = grainsInside ? R - rho : rho - R;  // centre-to-surface distance, grain side positive
    const double3 n = grainsInside ? -u : u;               // from the surface towards the grain
    c.overlap = rA - dist;
    c.B2A = to_float3(n);
    c.point = posA - n * (rA - 0.5 * c.overlap);
    return c;
}

// Signed distance from a point to an analytical surface, positive on the grain side. Used by
// contact detection, which must agree with the contact functions above.
DEME_HD inline double planeSignedDistance(const double3& p, const double3& planePoint, const double3& normal) {
    return dot(p - planePoint, normal);
}

DEME_HD inline double cylinderSignedDistance(const double3& p, const double3& axisPoint, const double3& axis, double R,
                                             bool grainsInside) {
    const double3 rel = p - axisPoint;
    const double3 radial = rel - axis * dot(rel, axis);
    const double rho = length(radial);
    return grainsInside ? R - rho : rho - R;
}

}  // namespace deme
