// Lattice samplers. Both samplers share one routine: lay a lattice over the region's bounding box,
// centred inside it, and keep the points that pass the region's inside test. Work is done in double
// so that float inputs far from the origin do not drift the lattice; points are rounded to float last.
#include <deme/Samplers.h>

#include <deme/Error.h>

#include <cmath>
#include <string>

namespace deme {
namespace {

constexpr double kPi = 3.14159265358979323846;

enum class Shape { Box, CylX, CylY, CylZ, Sphere };

struct Region {
    Shape shape;
    double c[3];         // centre
    double h[3];         // half extents of the bounding box
    double radius;       // cylinders and sphere
    double half_height;  // cylinders
};

void checkFinite(const std::string& call, const float3& v, const char* what) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throwError(call, std::string(what) + " must be finite");
}
void checkNonNeg(const std::string& call, float v, const char* what) {
    // !(v >= 0) also catches NaN.
    if (!(v >= 0.f) || !std::isfinite(v))
        throwError(call, std::string(what) + " must be finite and non-negative, got " + std::to_string(v));
}

bool inside(const Region& R, const double p[3], double tol) {
    double d[3] = {p[0] - R.c[0], p[1] - R.c[1], p[2] - R.c[2]};
    auto radial = [&](int a, int b, int axis) {
        double rr = R.radius + tol;
        return d[a] * d[a] + d[b] * d[b] <= rr * rr && std::fabs(d[axis]) <= R.half_height + tol;
    };
    switch (R.shape) {
        case Shape::Box:
            return std::fabs(d[0]) <= R.h[0] + tol && std::fabs(d[1]) <= R.h[1] + tol &&
                   std::fabs(d[2]) <= R.h[2] + tol;
        case Shape::CylX:
            return radial(1, 2, 0);
        case Shape::CylY:
            return radial(0, 2, 1);
        case Shape::CylZ:
            return radial(0, 1, 2);
        case Shape::Sphere: {
            double rr = R.radius + tol;
            return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= rr * rr;
        }
    }
    return false;
}

std::vector<float3> sample(const std::string& call, double s, bool hcp, const Region& R) {
    // HCP: pitch (s, s*sqrt(3)/2, s*sqrt(2/3)); odd rows / B layers are shifted in x by s/2 and
    // B layers in y by a third of the row pitch, so a B point sits over an A triangle's centroid:
    // (s/2)^2 + (py/3)^2 + pz^2 = s^2, i.e. 12 neighbours at exactly s.
    const double pitch[3] = {s, hcp ? s * std::sqrt(3.0) / 2 : s, hcp ? s * std::sqrt(2.0 / 3.0) : s};
    const double max_off[3] = {hcp ? s / 2 : 0.0, hcp ? pitch[1] / 3 : 0.0, 0.0};
    const double rel_eps = 1e-6;  // absorbs float round-off in inputs such as 2*0.3f/0.1f

    double start[3], ncand[3], approx = 1.0;
    double scale = s;
    for (int a = 0; a < 3; a++) {
        const double E = 2 * R.h[a];
        double margin;
        if (E >= max_off[a]) {
            // Largest lattice span (including the offset rows) that fits, then centre it.
            double n = std::floor((E - max_off[a]) / pitch[a] + rel_eps) + 1;
            margin = 0.5 * (E - ((n - 1) * pitch[a] + max_off[a]));
        } else {
            margin = 0.5 * E;  // region thinner than the offset: put the unshifted rows in the middle
        }
        start[a] = R.c[a] - R.h[a] + margin;
        // One spare candidate per axis; the inside test discards those that do not fit.
        ncand[a] = std::floor(E / pitch[a] + rel_eps) + 2;
        approx *= E / pitch[a] + 1;  // roughly the points per axis
        scale = std::fmax(scale, std::fabs(R.c[a]) + R.h[a]);
    }
    const double tol = rel_eps * scale;

    // Guard before allocating (and before the candidate loop, which could otherwise run for ages):
    // estimated points = lattice points in the bounding box * (region volume / bounding-box volume).
    double frac = 1.0;
    if (R.shape == Shape::Sphere)
        frac = kPi / 6;
    else if (R.shape != Shape::Box)
        frac = kPi / 4;
    const double estimate = approx * frac;
    if (!(estimate <= 2147483648.0))
        throwError(call, "region would hold about " + std::to_string(estimate) +
                             " points (more than 2^31); increase the spacing or shrink the region");

    std::vector<float3> pts;
    pts.reserve(static_cast<size_t>(estimate));
    const long nx = (long)ncand[0], ny = (long)ncand[1], nz = (long)ncand[2];
    for (long k = 0; k < nz; k++) {
        const bool layerB = hcp && (k & 1);
        for (long j = 0; j < ny; j++) {
            const bool shiftX = hcp && ((j + k) & 1);  // odd row in A, even row in B
            double p[3];
            p[2] = start[2] + k * pitch[2];
            p[1] = start[1] + j * pitch[1] + (layerB ? max_off[1] : 0.0);
            for (long i = 0; i < nx; i++) {
                p[0] = start[0] + i * pitch[0] + (shiftX ? max_off[0] : 0.0);
                if (inside(R, p, tol)) pts.push_back(make_float3((float)p[0], (float)p[1], (float)p[2]));
            }
        }
    }
    return pts;
}

float checkSpacing(const char* cls, float spacing) {
    if (!(spacing > 0.f) || !std::isfinite(spacing))
        throwError(cls, "spacing must be positive and finite, got " + std::to_string(spacing));
    return spacing;
}

Region box(const std::string& call, const float3& c, const float3& hd) {
    checkFinite(call, c, "center");
    checkNonNeg(call, hd.x, "half_dims.x");
    checkNonNeg(call, hd.y, "half_dims.y");
    checkNonNeg(call, hd.z, "half_dims.z");
    return Region{Shape::Box, {c.x, c.y, c.z}, {hd.x, hd.y, hd.z}, 0.0, 0.0};
}

Region cylinder(const std::string& call, Shape shape, const float3& c, float r, float hh) {
    checkFinite(call, c, "center");
    checkNonNeg(call, r, "radius");
    checkNonNeg(call, hh, "half_height");
    Region R{shape, {c.x, c.y, c.z}, {r, r, r}, r, hh};
    R.h[shape == Shape::CylX ? 0 : shape == Shape::CylY ? 1 : 2] = hh;
    return R;
}

Region sphere(const std::string& call, const float3& c, float r) {
    checkFinite(call, c, "center");
    checkNonNeg(call, r, "radius");
    return Region{Shape::Sphere, {c.x, c.y, c.z}, {r, r, r}, r, 0.0};
}

}  // namespace

// ---- HCPSampler ----
HCPSampler::HCPSampler(float spacing) : m_spacing(checkSpacing("HCPSampler", spacing)) {}

std::vector<float3> HCPSampler::SampleBox(const float3& center, const float3& half_dims) const {
    const std::string call = "HCPSampler::SampleBox";
    return sample(call, m_spacing, true, box(call, center, half_dims));
}
std::vector<float3> HCPSampler::SampleCylinderZ(const float3& center, float radius, float half_height) const {
    const std::string call = "HCPSampler::SampleCylinderZ";
    return sample(call, m_spacing, true, cylinder(call, Shape::CylZ, center, radius, half_height));
}
std::vector<float3> HCPSampler::SampleCylinderX(const float3& center, float radius, float half_height) const {
    const std::string call = "HCPSampler::SampleCylinderX";
    return sample(call, m_spacing, true, cylinder(call, Shape::CylX, center, radius, half_height));
}
std::vector<float3> HCPSampler::SampleCylinderY(const float3& center, float radius, float half_height) const {
    const std::string call = "HCPSampler::SampleCylinderY";
    return sample(call, m_spacing, true, cylinder(call, Shape::CylY, center, radius, half_height));
}
std::vector<float3> HCPSampler::SampleSphere(const float3& center, float radius) const {
    const std::string call = "HCPSampler::SampleSphere";
    return sample(call, m_spacing, true, sphere(call, center, radius));
}

// ---- GridSampler ----
GridSampler::GridSampler(float spacing) : m_spacing(checkSpacing("GridSampler", spacing)) {}

std::vector<float3> GridSampler::SampleBox(const float3& center, const float3& half_dims) const {
    const std::string call = "GridSampler::SampleBox";
    return sample(call, m_spacing, false, box(call, center, half_dims));
}
std::vector<float3> GridSampler::SampleCylinderZ(const float3& center, float radius, float half_height) const {
    const std::string call = "GridSampler::SampleCylinderZ";
    return sample(call, m_spacing, false, cylinder(call, Shape::CylZ, center, radius, half_height));
}
std::vector<float3> GridSampler::SampleCylinderX(const float3& center, float radius, float half_height) const {
    const std::string call = "GridSampler::SampleCylinderX";
    return sample(call, m_spacing, false, cylinder(call, Shape::CylX, center, radius, half_height));
}
std::vector<float3> GridSampler::SampleCylinderY(const float3& center, float radius, float half_height) const {
    const std::string call = "GridSampler::SampleCylinderY";
    return sample(call, m_spacing, false, cylinder(call, Shape::CylY, center, radius, half_height));
}
std::vector<float3> GridSampler::SampleSphere(const float3& center, float radius) const {
    const std::string call = "GridSampler::SampleSphere";
    return sample(call, m_spacing, false, sphere(call, center, radius));
}

}  // namespace deme
