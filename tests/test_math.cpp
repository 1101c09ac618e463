// Unit tests of the single-source physics helpers in src/physics/: quaternions, compact positions,
// contact geometry, material mixing and Euler's rotation equations. Expected values are computed by
// hand in the comments (or from the closed-form formulas quoted there), never by the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "physics/CompactPosition.h"
#include "physics/ContactGeometry.h"
#include "physics/MaterialMixing.h"
#include "physics/Quaternion.h"
#include "physics/RigidBody.h"
#include "state/OwnerCentre.h"

using namespace deme;

namespace {

void expectNear3(const float3& a, const float3& b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}
void expectNear3(const double3& a, const double3& b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// Rotation angle in [0, pi] of a unit quaternion: 2 atan2(|vector part|, |scalar part|).
double quatAngle(const float4& q) {
    const double v = std::sqrt((double)q.x * q.x + (double)q.y * q.y + (double)q.z * q.z);
    return 2.0 * std::atan2(v, std::fabs((double)q.w));
}

float4 conj(const float4& q) { return make_float4(-q.x, -q.y, -q.z, q.w); }

// The compact-position frame of a cube of edge L centred on the origin, built exactly as
// makeFrame() in src/api/SceneAssembly.cpp does: voxelSize = L / (2^21 - 1), subStep = voxelSize / 2^16.
DomainFrame cubeFrame(double L) {
    DomainFrame f;
    f.origin = make_double3(-0.5 * L, -0.5 * L, -0.5 * L);
    f.voxelSize = L / (double)((1 << VOXEL_BITS_PER_AXIS) - 1);
    f.subStep = f.voxelSize / SUBVOXEL_STEPS;
    return f;
}

const double kSqrtHalf = std::sqrt(0.5);

}  // namespace

// ---------------------------------------------------------------- quaternions

TEST(MathQuaternion, Rotate90DegreesAboutZ) {
    // 90 degrees about +z: q = (0, 0, sin 45, cos 45). By hand (right-hand rule): x -> y, y -> -x, z -> z.
    const float4 q = make_float4(0.f, 0.f, (float)kSqrtHalf, (float)kSqrtHalf);
    expectNear3(rotateToGlobal(q, make_float3(1, 0, 0)), make_float3(0, 1, 0), 1e-6);
    expectNear3(rotateToGlobal(q, make_float3(0, 1, 0)), make_float3(-1, 0, 0), 1e-6);
    expectNear3(rotateToGlobal(q, make_float3(0, 0, 1)), make_float3(0, 0, 1), 1e-6);
    // A general vector: (2, 3, -4) -> (-3, 2, -4).
    expectNear3(rotateToGlobal(q, make_float3(2, 3, -4)), make_float3(-3, 2, -4), 1e-5);
    // The inverse rotation (global -> local): y -> x, -x -> y.
    expectNear3(rotateToLocal(q, make_float3(0, 1, 0)), make_float3(1, 0, 0), 1e-6);
    expectNear3(rotateToLocal(q, make_float3(-1, 0, 0)), make_float3(0, 1, 0), 1e-6);
    expectNear3(rotateToLocal(q, make_float3(-3, 2, -4)), make_float3(2, 3, -4), 1e-5);
    // The double overload agrees with the float one.
    expectNear3(rotateToGlobal(q, make_double3(2, 3, -4)), make_double3(-3, 2, -4), 1e-6);
    // The paper's in-place helper, argument order (w, qx, qy, qz).
    float x = 1.f, y = 0.f, z = 0.f;
    applyOriQToVector3(x, y, z, q.w, q.x, q.y, q.z);
    expectNear3(make_float3(x, y, z), make_float3(0, 1, 0), 1e-6);
}

TEST(MathQuaternion, Rotate120DegreesAboutDiagonal) {
    // 120 degrees about (1,1,1)/sqrt(3) permutes the axes cyclically: x -> y -> z -> x.
    // q = (sin 60 / sqrt 3) (1,1,1) + cos 60 = (0.5, 0.5, 0.5, 0.5).
    const float4 q = make_float4(0.5f, 0.5f, 0.5f, 0.5f);
    expectNear3(rotateToGlobal(q, make_float3(1, 0, 0)), make_float3(0, 1, 0), 1e-6);
    expectNear3(rotateToGlobal(q, make_float3(0, 1, 0)), make_float3(0, 0, 1), 1e-6);
    expectNear3(rotateToGlobal(q, make_float3(0, 0, 1)), make_float3(1, 0, 0), 1e-6);
    expectNear3(rotateToLocal(q, make_float3(0, 0, 1)), make_float3(0, 1, 0), 1e-6);
}

TEST(MathQuaternion, RotateToLocalInvertsRotateToGlobal) {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    for (int i = 0; i < 1000; i++) {
        const float4 q = quatNormalize(make_float4(u(rng), u(rng), u(rng), u(rng)));
        const float3 v = make_float3(u(rng), u(rng), u(rng)) * 10.f;
        const float3 g = rotateToGlobal(q, v);
        // A rotation keeps the length (|v| <= 17.4, float round-off ~1e-6 relative).
        EXPECT_NEAR(length(g), length(v), 1e-4);
        expectNear3(rotateToLocal(q, g), v, 1e-4);
        expectNear3(rotateToGlobal(q, rotateToLocal(q, v)), v, 1e-4);
    }
}

TEST(MathQuaternion, MultiplyComposesRotations) {
    const float4 qz = make_float4(0.f, 0.f, (float)kSqrtHalf, (float)kSqrtHalf);  // 90 deg about z
    const float4 qx = make_float4((float)kSqrtHalf, 0.f, 0.f, (float)kSqrtHalf);  // 90 deg about x
    // Two 90-degree turns about z are 180 degrees about z: (0, 0, 1, 0) (up to sign).
    const float4 zz = quatMultiply(qz, qz);
    EXPECT_NEAR(zz.x, 0.f, 1e-6);
    EXPECT_NEAR(zz.y, 0.f, 1e-6);
    EXPECT_NEAR(std::fabs(zz.z), 1.f, 1e-6);
    EXPECT_NEAR(zz.w, 0.f, 1e-6);
    // quatMultiply(a, b) applies b first, then a. By hand, for v = y:
    //   qz*qx: x-turn y -> z, then z-turn z -> z: result z.
    //   qx*qz: z-turn y -> -x, then x-turn -x -> -x: result -x.
    expectNear3(rotateToGlobal(quatMultiply(qz, qx), make_float3(0, 1, 0)), make_float3(0, 0, 1), 1e-6);
    expectNear3(rotateToGlobal(quatMultiply(qx, qz), make_float3(0, 1, 0)), make_float3(-1, 0, 0), 1e-6);
    // Hamilton product by hand: qz*qx = (0.5, 0.5, 0.5, 0.5), the 120-degree diagonal turn.
    const float4 zx = quatMultiply(qz, qx);
    EXPECT_NEAR(zx.x, 0.5f, 1e-6);
    EXPECT_NEAR(zx.y, 0.5f, 1e-6);
    EXPECT_NEAR(zx.z, 0.5f, 1e-6);
    EXPECT_NEAR(zx.w, 0.5f, 1e-6);
    // Random pairs: rotating by a*b equals rotating by b, then by a.
    std::mt19937 rng(777);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    for (int i = 0; i < 500; i++) {
        const float4 a = quatNormalize(make_float4(u(rng), u(rng), u(rng), u(rng)));
        const float4 b = quatNormalize(make_float4(u(rng), u(rng), u(rng), u(rng)));
        const float3 v = make_float3(u(rng), u(rng), u(rng));
        expectNear3(rotateToGlobal(quatMultiply(a, b), v), rotateToGlobal(a, rotateToGlobal(b, v)), 1e-5);
    }
}

TEST(MathQuaternion, IntegrateOrientationTurnsByOmegaDt) {
    // Constant body-frame w = (0.3, -0.4, 1.2) rad/s, |w| = 1.3 rad/s.
    const float3 w = make_float3(0.3f, -0.4f, 1.2f);
    const double wmag = 1.3;
    const float4 q0 = quatNormalize(make_float4(0.1f, 0.7f, -0.2f, 0.6f));
    // One step of dt = 0.5 s: relative turn conj(q0)*q1 has angle |w| dt = 0.65 rad about w/|w|.
    {
        const float4 q1 = integrateOrientation(q0, w, 0.5f);
        const float4 dq = quatMultiply(conj(q0), q1);
        EXPECT_NEAR(quatAngle(dq), wmag * 0.5, 1e-5);
        // Axis of the body-frame increment is w/|w| (sign of dq chosen so that its scalar part is >= 0).
        const double s = dq.w >= 0.f ? 1.0 : -1.0;
        const double vn = std::sqrt((double)dq.x * dq.x + (double)dq.y * dq.y + (double)dq.z * dq.z);
        EXPECT_NEAR(s * dq.x / vn, 0.3 / wmag, 1e-5);
        EXPECT_NEAR(s * dq.y / vn, -0.4 / wmag, 1e-5);
        EXPECT_NEAR(s * dq.z / vn, 1.2 / wmag, 1e-5);
        // The result stays a unit quaternion.
        EXPECT_NEAR((double)q1.x * q1.x + (double)q1.y * q1.y + (double)q1.z * q1.z + (double)q1.w * q1.w, 1.0, 1e-6);
    }
    // Twenty steps of dt = 0.1 s: 2.6 rad in total (< pi, so the angle is unambiguous).
    {
        float4 q = q0;
        for (int i = 0; i < 20; i++) q = integrateOrientation(q, w, 0.1f);
        EXPECT_NEAR(quatAngle(quatMultiply(conj(q0), q)), wmag * 2.0, 1e-5);
    }
    // A spin about local z from identity: the local x axis ends up at (cos a, sin a, 0), a = 2 * 0.4.
    {
        const float4 q = integrateOrientation(make_float4(0, 0, 0, 1), make_float3(0, 0, 2.f), 0.4f);
        expectNear3(rotateToGlobal(q, make_float3(1, 0, 0)), make_float3((float)std::cos(0.8), (float)std::sin(0.8), 0),
                    1e-6);
    }
    // Zero angular velocity leaves q unchanged.
    const float4 same = integrateOrientation(q0, make_float3(0.f), 0.1f);
    EXPECT_EQ(same.x, q0.x);
    EXPECT_EQ(same.y, q0.y);
    EXPECT_EQ(same.z, q0.z);
    EXPECT_EQ(same.w, q0.w);
}

// ---------------------------------------------------------------- compact positions

TEST(MathCompactPosition, ResolutionIsTwoToMinus37InOneMetreDomain) {
    const DomainFrame f = cubeFrame(1.0);
    // subStep = 1 / ((2^21 - 1) * 2^16) m = 2^-37 * 2^21 / (2^21 - 1): 2^-37 m to a relative 4.8e-7.
    const double twoM37 = std::ldexp(1.0, -37);  // 7.275957614183426e-12 m
    EXPECT_NEAR(f.subStep / twoM37, 1.0, 1e-6);
    EXPECT_NEAR(f.subStep, 7.27596e-12, 1e-16);
    // Neighbouring codes decode one step apart, also across a voxel boundary (to the double spacing
    // near 0.5 m, 5.6e-17 m, i.e. 1e-5 of a step).
    const double a = decodeAxis(5, 65535, f.origin.x, f.subStep);
    const double b = decodeAxis(6, 0, f.origin.x, f.subStep);
    EXPECT_NEAR(b - a, f.subStep, 1e-16);
    EXPECT_NEAR(decodeAxis(5, 1, f.origin.x, f.subStep) - decodeAxis(5, 0, f.origin.x, f.subStep), f.subStep, 1e-16);
    // Voxel (0, 0) is the lower corner.
    EXPECT_EQ(decodeAxis(0, 0, f.origin.x, f.subStep), -0.5);
}

TEST(MathCompactPosition, RoundTripErrorAtMostHalfStep) {
    const DomainFrame f = cubeFrame(1.0);
    const double half = 0.5 * f.subStep;
    // Allowance for double round-off in (p - origin) / subStep (~1e-16 relative of ~1.4e11 steps).
    const double tol = half + 1e-16;
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    double worst = 0.0;
    for (int i = 0; i < 100000; i++) {
        const double3 p = make_double3(u(rng), u(rng), u(rng));
        voxelID_t v;
        subVoxelPos_t sx, sy, sz;
        ASSERT_TRUE(encodePosition(p, f, v, sx, sy, sz)) << p.x << " " << p.y << " " << p.z;
        const double3 d = decodePosition(v, sx, sy, sz, f);
        worst = std::max({worst, std::fabs(d.x - p.x), std::fabs(d.y - p.y), std::fabs(d.z - p.z)});
    }
    EXPECT_LE(worst, tol);
    // The rounding error is uniform on [-subStep/2, subStep/2]: over 3e5 samples the worst one is close
    // to half a step (guards against a degenerate frame in which nothing is rounded at all).
    EXPECT_GT(worst, 0.45 * f.subStep);

    // Faces and corners of the domain are representable.
    for (double x : {-0.5, 0.5})
        for (double z : {-0.5, 0.5}) {
            const double3 p = make_double3(x, 0.5, z);
            voxelID_t v;
            subVoxelPos_t sx, sy, sz;
            ASSERT_TRUE(encodePosition(p, f, v, sx, sy, sz));
            const double3 d = decodePosition(v, sx, sy, sz, f);
            expectNear3(d, p, tol);
        }
    // A point one step above a code decodes to that code + 1 (the packed voxel and sub-voxel agree).
    {
        const double3 p = make_double3(decodeAxis(7, 65535, -0.5, f.subStep) + f.subStep, 0.0, 0.0);
        voxelID_t v;
        subVoxelPos_t sx, sy, sz;
        ASSERT_TRUE(encodePosition(p, f, v, sx, sy, sz));
        uint64_t vx, vy, vz;
        unpackVoxel(v, vx, vy, vz);
        EXPECT_EQ(vx, 8u);
        EXPECT_EQ(sx, 0u);
    }
}

TEST(MathCompactPosition, PackUnpackVoxel) {
    const uint64_t mx = (uint64_t(1) << VOXEL_BITS_PER_AXIS) - 1;  // 2^21 - 1 per axis
    uint64_t x, y, z;
    unpackVoxel(packVoxel(mx, 0, 12345), x, y, z);
    EXPECT_EQ(x, mx);
    EXPECT_EQ(y, 0u);
    EXPECT_EQ(z, 12345u);
    unpackVoxel(packVoxel(1, mx, mx), x, y, z);
    EXPECT_EQ(x, 1u);
    EXPECT_EQ(y, mx);
    EXPECT_EQ(z, mx);
}

TEST(MathCompactPosition, EncodeRejectsOutsideAndNaN) {
    const DomainFrame f = cubeFrame(1.0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    // Outside the 1 m box centred on the origin (the representable range ends one voxel, ~4.8e-7 m,
    // past the far faces), NaN and infinities in any component.
    const double3 bad[] = {make_double3(0.6, 0, 0),        make_double3(-0.6, 0, 0), make_double3(0, 0.6, 0),
                           make_double3(0, -0.51, 0),      make_double3(0, 0, 1.0),  make_double3(0, 0, -0.500001),
                           make_double3(0.5 + 1e-6, 0, 0), make_double3(nan, 0, 0),  make_double3(0, nan, 0),
                           make_double3(0, 0, nan),        make_double3(inf, 0, 0),  make_double3(0, -inf, 0)};
    for (const double3& p : bad) {
        SCOPED_TRACE(std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z));
        // Sentinels: a rejected point leaves the outputs untouched (documented in CompactPosition.h).
        voxelID_t v = 42;
        subVoxelPos_t sx = 1, sy = 2, sz = 3;
        EXPECT_FALSE(encodePosition(p, f, v, sx, sy, sz));
        EXPECT_EQ(v, 42u);
        EXPECT_EQ(sx, 1u);
        EXPECT_EQ(sy, 2u);
        EXPECT_EQ(sz, 3u);
    }
}

// The force pass's voxel pretest (state/OwnerCentre.h, apartByVoxelCodes) may turn a pair away
// only where its decoded centres are farther apart than the reach: pairs placed at random around
// the reach (at it exactly, and within a hundredth of it in a fine frame: a 0.3 m domain, voxels of
// 0.14 um against a 2 mm reach; from half to three times it in a coarse one: a 2,000 m domain,
// voxels of 1 mm, a pair's voxels a few apart along an axis), never one within reach. In the fine frame every pair
// more than a thousandth of the reach apart is turned away (the bound loses at most two voxels an
// axis, 0.5 um in all).
TEST(MathCompactPosition, VoxelCodesNeverPartAPairWithinReach) {
    struct {
        struct {
            std::vector<voxelID_t> voxel;
        } owners;
        DomainFrame frame;
    } s;
    const double reach = 2e-3;
    for (double L : {0.3, 2000.0}) {
        SCOPED_TRACE("domain " + std::to_string(L) + " m");
        s.frame = cubeFrame(L);
        std::mt19937_64 rng(17);
        const bool fine = L < 1.0;
        std::uniform_real_distribution<double> u(-0.4 * L, 0.4 * L), dir(-1.0, 1.0),
            rel(fine ? -0.01 : -0.5, fine ? 0.01 : 2.0);
        size_t within = 0, turnedAway = 0, farTurnedAway = 0, far = 0;
        for (int i = 0; i < 200000; i++) {
            const double3 a = make_double3(u(rng), u(rng), u(rng));
            double3 n = make_double3(dir(rng), dir(rng), dir(rng));
            n = n / std::sqrt(dot(n, n));
            const double d = reach * (i % 10 == 0 ? 1.0 : 1.0 + rel(rng));
            const double3 b = a + d * n;
            s.owners.voxel.assign(2, 0);
            subVoxelPos_t sub[6];
            ASSERT_TRUE(encodePosition(a, s.frame, s.owners.voxel[0], sub[0], sub[1], sub[2]));
            ASSERT_TRUE(encodePosition(b, s.frame, s.owners.voxel[1], sub[3], sub[4], sub[5]));
            const double3 pa = decodePosition(s.owners.voxel[0], sub[0], sub[1], sub[2], s.frame);
            const double3 pb = decodePosition(s.owners.voxel[1], sub[3], sub[4], sub[5], s.frame);
            const double dist = std::sqrt(dot(pa - pb, pa - pb));
            const bool apart = apartByVoxelCodes(s, 0, 1, reach);
            if (dist <= reach) {
                within++;
                ASSERT_FALSE(apart) << "a pair " << dist << " m apart, reach " << reach;
            }
            turnedAway += apart;
            if (dist > 1.001 * reach) {
                far++;
                farTurnedAway += apart;
            }
        }
        EXPECT_GT(within, 20000u);  // the test saw many pairs within reach
        EXPECT_GT(turnedAway, 20000u);
        if (fine) EXPECT_EQ(farTurnedAway, far);
    }
}

// ---------------------------------------------------------------- contact geometry

// A clump parked by the "remove" exit policy has a code no position has (PARKED_VOXEL): where the
// frame parks, its centre is its place on the frame's parking line (1000 domain lengths out along
// x, 4 apart); otherwise, and for every other code, the decoded position (state/OwnerCentre.h).
TEST(MathCompactPosition, ParkedCodeReadsAsItsPlaceOnTheParkingLine) {
    DomainFrame f = cubeFrame(2.0);
    f.periodic.length = make_double3(2.0, 2.0, 2.0);
    f.parking = parkingLine(f);
    const double3 p = make_double3(0.3, -0.2, 0.7);
    voxelID_t v = 0;
    subVoxelPos_t sx = 0, sy = 0, sz = 0;
    ASSERT_TRUE(encodePosition(p, f, v, sx, sy, sz));
    EXPECT_EQ(v & PARKED_VOXEL, 0u);  // no position's code has the bit
    const size_t o = 7;
    f.parks = true;
    expectNear3(ownerCentreOfCode(v, sx, sy, sz, f, o), decodePosition(v, sx, sy, sz, f), 0.0);
    const double3 parked = ownerCentreOfCode(v | PARKED_VOXEL, sx, sy, sz, f, o);
    expectNear3(parked, make_double3(-1.0 + (1000.0 + 4.0 * o) * 2.0, -1.0, -1.0), 1e-9);
    f.parks = false;  // a frame that parks nothing reads no parking line
    expectNear3(ownerCentreOfCode(v | PARKED_VOXEL, sx, sy, sz, f, o), decodePosition(v, sx, sy, sz, f), 0.0);
}

TEST(MathContactGeometry, SphereSphere) {
    // A (r 0.01) at z = 0.018 above B (r 0.01) at the origin: overlap 0.01 + 0.01 - 0.018 = 0.002,
    // B2A = +z, contact point in the middle of the overlap: z = 0.01 - 0.001 = 0.009.
    {
        const ContactPoint c = sphereSphereContact(make_double3(0, 0, 0.018), 0.01, make_double3(0, 0, 0), 0.01);
        EXPECT_NEAR(c.overlap, 0.002, 1e-12);
        expectNear3(c.B2A, make_float3(0, 0, 1), 1e-7);
        expectNear3(c.point, make_double3(0, 0, 0.009), 1e-12);
    }
    // Unequal radii, off-axis: A (r 0.03) at (0.03, 0.04, 0.1), B (r 0.025) at (0, 0, 0.1).
    // Distance 0.05, overlap 0.005, B2A = (0.6, 0.8, 0); the point is B + n * (0.025 - 0.0025).
    {
        const ContactPoint c = sphereSphereContact(make_double3(0.03, 0.04, 0.1), 0.03, make_double3(0, 0, 0.1), 0.025);
        EXPECT_NEAR(c.overlap, 0.005, 1e-12);
        expectNear3(c.B2A, make_float3(0.6f, 0.8f, 0), 1e-7);
        expectNear3(c.point, make_double3(0.6 * 0.0225, 0.8 * 0.0225, 0.1), 1e-12);
    }
    // Apart by 0.01 along -x: overlap -0.01, normal points from B to A (-x).
    {
        const ContactPoint c = sphereSphereContact(make_double3(-0.03, 0, 0), 0.01, make_double3(0, 0, 0), 0.01);
        EXPECT_NEAR(c.overlap, -0.01, 1e-12);
        expectNear3(c.B2A, make_float3(-1, 0, 0), 1e-7);
    }
}

TEST(MathContactGeometry, SpherePlane) {
    // Floor z = -0.5 with normal +z; sphere r 0.01 at z = -0.495 is 0.005 above it: overlap 0.005.
    // Midpoint between the sphere bottom (-0.505) and the plane (-0.5): z = -0.5025.
    {
        const ContactPoint c = spherePlaneContact(make_double3(0.1, 0.2, -0.495), 0.01, make_double3(0.3, -0.1, -0.5),
                                                  make_double3(0, 0, 1));
        EXPECT_NEAR(c.overlap, 0.005, 1e-12);
        expectNear3(c.B2A, make_float3(0, 0, 1), 1e-7);
        expectNear3(c.point, make_double3(0.1, 0.2, -0.5025), 1e-12);
    }
    // Tilted plane through the origin, n = (0.6, 0, 0.8), tangent t = (0.8, 0, -0.6). Sphere r 0.01 at
    // 0.3 t + 0.008 n: overlap 0.002, point = centre - n (0.01 - 0.001) = 0.3 t - 0.001 n.
    {
        const double3 n = make_double3(0.6, 0, 0.8), t = make_double3(0.8, 0, -0.6);
        const ContactPoint c = spherePlaneContact(t * 0.3 + n * 0.008, 0.01, make_double3(0, 0, 0), n);
        EXPECT_NEAR(c.overlap, 0.002, 1e-12);
        expectNear3(c.B2A, make_float3(0.6f, 0, 0.8f), 1e-7);
        expectNear3(c.point, t * 0.3 - n * 0.001, 1e-12);
    }
    // Centre 0.02 above the plane: apart by 0.01, overlap -0.01.
    EXPECT_NEAR(
        spherePlaneContact(make_double3(0, 0, 0.02), 0.01, make_double3(0, 0, 0), make_double3(0, 0, 1)).overlap, -0.01,
        1e-12);
}

TEST(MathContactGeometry, SphereCylinderInside) {
    // Drum of radius 0.1 about the z axis, grains inside. Sphere r 0.01 at radial distance 0.095 along
    // u = (0.6, 0.8, 0), height 0.3: gap to the wall 0.005, overlap 0.005, normal towards the axis (-u),
    // point midway between the sphere's outermost point (0.105) and the wall (0.1): 0.1025 u.
    const ContactPoint c = sphereCylinderContact(make_double3(0.6 * 0.095, 0.8 * 0.095, 0.3), 0.01,
                                                 make_double3(0, 0, -1.0), make_double3(0, 0, 1), 0.1, true);
    EXPECT_NEAR(c.overlap, 0.005, 1e-12);
    expectNear3(c.B2A, make_float3(-0.6f, -0.8f, 0), 1e-7);
    expectNear3(c.point, make_double3(0.6 * 0.1025, 0.8 * 0.1025, 0.3), 1e-12);
    // Near the axis, far from the wall: overlap = r - (R - rho) = 0.01 - 0.09 = -0.08.
    EXPECT_NEAR(
        sphereCylinderContact(make_double3(0.01, 0, 0), 0.01, make_double3(0, 0, 0), make_double3(0, 0, 1), 0.1, true)
            .overlap,
        -0.08, 1e-12);
    // Agrees with the signed distance used by contact detection: overlap = r - distance.
    EXPECT_NEAR(cylinderSignedDistance(make_double3(0.6 * 0.095, 0.8 * 0.095, 0.3), make_double3(0, 0, -1.0),
                                       make_double3(0, 0, 1), 0.1, true),
                0.005, 1e-12);
}

TEST(MathContactGeometry, SphereCylinderOutside) {
    // Post of radius 0.1 along the y axis through (0.2, 0, 0), grains outside. Sphere r 0.01 at radial
    // distance 0.105 along u = (0.8, 0, -0.6) from the axis, y = -0.4: gap 0.005, overlap 0.005,
    // normal u (away from the axis), point midway between the sphere's innermost point (0.095) and
    // the surface (0.1): axis point + 0.0975 u.
    const double3 axisPt = make_double3(0.2, 0, 0);
    const double3 u = make_double3(0.8, 0, -0.6);
    const double3 centre = axisPt + u * 0.105 + make_double3(0, -0.4, 0);
    const ContactPoint c = sphereCylinderContact(centre, 0.01, axisPt, make_double3(0, 1, 0), 0.1, false);
    EXPECT_NEAR(c.overlap, 0.005, 1e-12);
    expectNear3(c.B2A, make_float3(0.8f, 0, -0.6f), 1e-7);
    expectNear3(c.point, axisPt + u * 0.0975 + make_double3(0, -0.4, 0), 1e-12);
    // Centre at radial distance 0.21: 0.11 from the surface, overlap 0.01 - 0.11 = -0.1.
    EXPECT_NEAR(sphereCylinderContact(axisPt + u * 0.21, 0.01, axisPt, make_double3(0, 1, 0), 0.1, false).overlap, -0.1,
                1e-12);
}

// ---------------------------------------------------------------- material mixing

TEST(MathMaterialMixing, IdenticalMaterials) {
    // Hertz with identical materials: E* = E / (2 (1 - nu^2)), G* = E / (4 (2 - nu)(1 + nu)).
    // E = 1e8, nu = 0.3: E* = 1e8 / 1.82 = 5.494505e7, G* = 1e8 / 8.84 = 1.131222e7.
    float Eeff = 0.f, Geff = 0.f;
    matProxy2ContactParam(Eeff, Geff, 1e8f, 0.3f, 1e8f, 0.3f);
    EXPECT_NEAR(Eeff / 5.4945054945e7, 1.0, 1e-6);
    EXPECT_NEAR(Geff / 1.1312217195e7, 1.0, 1e-6);
    // Another pair of values, formula evaluated in double: E = 7e10, nu = 0.22.
    matProxy2ContactParam(Eeff, Geff, 7e10f, 0.22f, 7e10f, 0.22f);
    EXPECT_NEAR(Eeff / (7e10 / (2.0 * (1.0 - 0.22 * 0.22))), 1.0, 1e-6);
    EXPECT_NEAR(Geff / (7e10 / (4.0 * (2.0 - 0.22) * (1.0 + 0.22))), 1.0, 1e-6);
}

TEST(MathMaterialMixing, DifferentMaterialsAreSymmetric) {
    // 1/E* = (1 - nuA^2)/EA + (1 - nuB^2)/EB, 1/G* = 2(2 - nuA)(1 + nuA)/EA + 2(2 - nuB)(1 + nuB)/EB.
    const double EA = 1e8, nuA = 0.3, EB = 2e9, nuB = 0.25;
    const double Eexp = 1.0 / ((1 - nuA * nuA) / EA + (1 - nuB * nuB) / EB);
    const double Gexp = 1.0 / (2 * (2 - nuA) * (1 + nuA) / EA + 2 * (2 - nuB) * (1 + nuB) / EB);
    float E1, G1, E2, G2;
    matProxy2ContactParam(E1, G1, (float)EA, (float)nuA, (float)EB, (float)nuB);
    matProxy2ContactParam(E2, G2, (float)EB, (float)nuB, (float)EA, (float)nuA);
    EXPECT_NEAR(E1 / Eexp, 1.0, 1e-6);
    EXPECT_NEAR(G1 / Gexp, 1.0, 1e-6);
    EXPECT_NEAR(E2 / E1, 1.0, 1e-6);
    EXPECT_NEAR(G2 / G1, 1.0, 1e-6);
}

// ---------------------------------------------------------------- rigid body

TEST(MathRigidBody, TorqueFreeSymmetricBodyKeepsSpinAboutAxis) {
    // Symmetric top: I1 = I2 = 0.3, I3 = 0.7 (symmetry axis z). Euler's equations without torque:
    //   dw1/dt = -(I3 - I2)/I1 w2 w3,  dw2/dt = -(I1 - I3)/I2 w3 w1,  dw3/dt = -(I2 - I1)/I3 w1 w2 = 0.
    const float3 moi = make_float3(0.3f, 0.3f, 0.7f);
    const float3 w = make_float3(0.5f, -1.3f, 2.1f);
    const float3 a = eulerAngularAcc(w, make_float3(0.f), moi);
    EXPECT_NEAR(a.z, 0.0, 1e-6);
    const double w1 = 0.5, w2 = -1.3, w3 = 2.1;
    EXPECT_NEAR(a.x, -(0.7 - 0.3) / 0.3 * w2 * w3, 1e-5);  // = 3.64
    EXPECT_NEAR(a.y, -(0.3 - 0.7) / 0.3 * w3 * w1, 1e-5);  // = 1.4
    // Spin purely about the symmetry axis: no acceleration at all.
    expectNear3(eulerAngularAcc(make_float3(0, 0, 5.f), make_float3(0.f), moi), make_float3(0.f), 1e-7);
    // At rest, the acceleration is torque / I component-wise.
    expectNear3(eulerAngularAcc(make_float3(0.f), make_float3(0.3f, 0.6f, 1.4f), moi), make_float3(1.f, 2.f, 2.f),
                1e-6);
    // Many steps of the midpoint integrator keep w3 constant (symmetric body, no torque).
    float3 ww = w;
    const float3 invMoi = make_float3(1.f / moi.x, 1.f / moi.y, 1.f / moi.z);
    for (int i = 0; i < 1000; i++) ww = advanceAngularVelocity(ww, make_float3(0.f), moi, invMoi, 1e-3f).wEnd;
    EXPECT_NEAR(ww.z, 2.1f, 1e-5);
    // And |w_perp| is conserved to the integrator's accuracy (the transverse part precesses).
    EXPECT_NEAR(std::sqrt((double)ww.x * ww.x + (double)ww.y * ww.y), std::sqrt(w1 * w1 + w2 * w2), 1e-3);
}

TEST(MathRigidBody, LocalPointToGlobal) {
    // Owner at (1, 2, 3) turned 90 degrees about z: local (0.1, 0, 0) is at (1, 2.1, 3).
    const float4 q = make_float4(0.f, 0.f, (float)kSqrtHalf, (float)kSqrtHalf);
    expectNear3(localPointToGlobal(make_double3(1, 2, 3), q, make_float3(0.1f, 0, 0)), make_double3(1, 2.1, 3), 1e-7);
}
