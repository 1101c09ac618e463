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
    const double3 n = dist > 0.0 ? d * (1.0 / dist) : make_double3(0.0, 0.0, 1.0);
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
        u = radial * (1.0 / rho);  // one division, not three (each a long sequence on a GPU)
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

// Closest point of triangle (a, b, c) to p, with its barycentric coordinates (point = bary.x a +
// bary.y b + bary.z c). Voronoi-region walk after Ericson, Real-Time Collision Detection, 5.1.5.
DEME_HD inline double3 closestPointOnTriangle(const double3& p, const double3& a, const double3& b, const double3& c,
                                              double3& bary) {
    const double3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
        bary = make_double3(1.0, 0.0, 0.0);
        return a;
    }
    const double3 bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) {
        bary = make_double3(0.0, 1.0, 0.0);
        return b;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        const double v = d1 / (d1 - d3);
        bary = make_double3(1.0 - v, v, 0.0);
        return a + ab * v;
    }
    const double3 cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) {
        bary = make_double3(0.0, 0.0, 1.0);
        return c;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        const double w = d2 / (d2 - d6);
        bary = make_double3(1.0 - w, 0.0, w);
        return a + ac * w;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        bary = make_double3(0.0, 1.0 - w, w);
        return b + (c - b) * w;
    }
    const double denom = 1.0 / (va + vb + vc);
    const double v = vb * denom, w = vc * denom;
    bary = make_double3(1.0 - v - w, v, w);
    return a + ab * v + ac * w;
}

// Sphere against its closest point `onTri` of a triangle with unit normal `faceNormal` (used only
// when the centre lies on the triangle itself). Triangles are two-sided.
DEME_HD inline ContactPoint sphereTriangleContact(const double3& posA, double rA, const double3& onTri,
                                                  const double3& faceNormal) {
    ContactPoint c;
    const double3 d = posA - onTri;
    const double dist = length(d);
    const double3 n = dist > 0.0 ? d / dist : faceNormal;
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
