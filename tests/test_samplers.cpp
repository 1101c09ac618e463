#include <deme/Error.h>
#include <deme/Samplers.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

using namespace deme;

namespace {

const double kPi = 3.14159265358979323846;

// Float rounding of the output points is the only slack the sampler may take.
bool approxLE(double a, double b, double scale) { return a <= b + 1e-5 * scale; }

struct Case {
    const char* name;
    std::function<std::vector<float3>()> run;
    std::function<bool(const float3&)> inside;
};

// Every region kind for one sampler, small enough for brute-force pair checks.
template <class S>
std::vector<Case> cases(const S& smp) {
    const float3 c = make_float3(0.3f, -1.2f, 2.5f);
    const float3 h = make_float3(1.1f, 0.7f, 0.9f);
    const float r = 1.05f, hh = 0.8f;
    auto cyl = [=](int axis) {
        return [=](const float3& p) {
            double d[3] = {p.x - c.x, p.y - c.y, p.z - c.z};
            double rad2 = 0;
            for (int a = 0; a < 3; a++)
                if (a != axis) rad2 += d[a] * d[a];
            return approxLE(std::sqrt(rad2), r, 4) && approxLE(std::fabs(d[axis]), hh, 4);
        };
    };
    return {
        {"Box", [=] { return smp.SampleBox(c, h); },
         [=](const float3& p) {
             return approxLE(std::fabs(p.x - c.x), h.x, 4) && approxLE(std::fabs(p.y - c.y), h.y, 4) &&
                    approxLE(std::fabs(p.z - c.z), h.z, 4);
         }},
        {"CylinderX", [=] { return smp.SampleCylinderX(c, r, hh); }, cyl(0)},
        {"CylinderY", [=] { return smp.SampleCylinderY(c, r, hh); }, cyl(1)},
        {"CylinderZ", [=] { return smp.SampleCylinderZ(c, r, hh); }, cyl(2)},
        {"Sphere", [=] { return smp.SampleSphere(c, r); },
         [=](const float3& p) { return approxLE(length(p - c), r, 4); }},
    };
}

double minPairDistance(const std::vector<float3>& pts) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < pts.size(); i++)
        for (size_t j = i + 1; j < pts.size(); j++) best = std::min(best, (double)length(pts[i] - pts[j]));
    return best;
}

template <class S>
void checkSampler(const S& smp) {
    for (const Case& cs : cases(smp)) {
        SCOPED_TRACE(cs.name);
        const std::vector<float3> pts = cs.run();
        ASSERT_GT(pts.size(), 10u);
        for (const float3& p : pts) ASSERT_TRUE(cs.inside(p)) << p.x << " " << p.y << " " << p.z;
        EXPECT_NEAR(minPairDistance(pts), smp.GetSpacing(), 1e-5 * smp.GetSpacing());
        // Deterministic, z-major then y then x.
        const std::vector<float3> again = cs.run();
        ASSERT_EQ(again.size(), pts.size());
        EXPECT_EQ(0, std::memcmp(again.data(), pts.data(), pts.size() * sizeof(float3)));
        for (size_t i = 1; i < pts.size(); i++) {
            const float3 &a = pts[i - 1], &b = pts[i];
            ASSERT_TRUE(a.z < b.z || (a.z == b.z && (a.y < b.y || (a.y == b.y && a.x < b.x)))) << i;
        }
    }
}

}  // namespace

TEST(Samplers, HCPPointsInsideAndSpacing) { checkSampler(HCPSampler(0.25f)); }
TEST(Samplers, GridPointsInsideAndSpacing) { checkSampler(GridSampler(0.2f)); }

TEST(Samplers, HCPHasTwelveNeighbours) {
    const float s = 0.5f;
    const float3 c = make_float3(1.f, 2.f, 3.f);
    std::vector<float3> pts = HCPSampler(s).SampleBox(c, make_float3(2.f));
    // The point nearest the centre is deep inside: exactly 12 neighbours at s, none closer.
    const float3 mid = *std::min_element(
        pts.begin(), pts.end(), [&](const float3& a, const float3& b) { return length(a - c) < length(b - c); });
    int n = 0;
    for (const float3& p : pts) {
        const double d = length(p - mid);
        if (d > 0 && d < 1.01 * s) {
            EXPECT_NEAR(d, s, 1e-5 * s);
            n++;
        }
    }
    EXPECT_EQ(n, 12);
}

TEST(Samplers, HCPDensityMatchesClosePacking) {
    const float s = 1.f, h = 50.f;
    const size_t n = HCPSampler(s).SampleBox(make_float3(0.f), make_float3(h)).size();
    const double fill = n * (kPi / 6 * s * s * s) / std::pow(2.0 * h, 3);
    EXPECT_NEAR(fill / (kPi / (3 * std::sqrt(2.0))), 1.0, 0.05);
}

TEST(Samplers, BoxFilledSymmetrically) {
    const float3 c = make_float3(-0.4f, 0.9f, 0.1f), h = make_float3(1.3f, 0.95f, 1.7f);
    for (int hcp = 0; hcp < 2; hcp++) {
        const float s = 0.3f;
        std::vector<float3> pts = hcp ? HCPSampler(s).SampleBox(c, h) : GridSampler(s).SampleBox(c, h);
        float3 lo = pts[0], hi = pts[0];
        for (const float3& p : pts) {
            lo = make_float3(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
            hi = make_float3(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
        }
        // Gaps to the walls are equal on both sides of every axis.
        EXPECT_NEAR(lo.x - (c.x - h.x), (c.x + h.x) - hi.x, 1e-4) << hcp;
        EXPECT_NEAR(lo.y - (c.y - h.y), (c.y + h.y) - hi.y, 1e-4) << hcp;
        EXPECT_NEAR(lo.z - (c.z - h.z), (c.z + h.z) - hi.z, 1e-4) << hcp;
    }
}

TEST(Samplers, GridBoxCountExact) {
    const float s = 0.1f;
    // h multiple of s: ((2h/s)+1) points per axis, corners on the box faces.
    EXPECT_EQ(GridSampler(s).SampleBox(make_float3(3.f, -2.f, 7.f), make_float3(0.5f, 0.3f, 0.2f)).size(),
              11u * 7u * 5u);
    EXPECT_EQ(GridSampler(2.f).SampleBox(make_float3(0.f), make_float3(10.f)).size(), 11u * 11u * 11u);
    // Degenerate box: just the centre.
    std::vector<float3> one = GridSampler(1.f).SampleBox(make_float3(1.f, 2.f, 3.f), make_float3(0.f));
    ASSERT_EQ(one.size(), 1u);
    EXPECT_FLOAT_EQ(one[0].y, 2.f);
}

TEST(Samplers, ErrorsThrow) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (float bad : {0.f, -1.f, nan, inf}) {
        EXPECT_THROW(HCPSampler{bad}, Error);
        EXPECT_THROW(GridSampler{bad}, Error);
    }
    auto expectMsg = [](const std::function<void()>& f, const std::string& call) {
        try {
            f();
            ADD_FAILURE() << "no throw for " << call;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(call), std::string::npos) << e.what();
        }
    };
    const HCPSampler hcp(0.1f);
    const GridSampler grid(0.1f);
    const float3 o = make_float3(0.f);
    expectMsg([&] { hcp.SampleBox(o, make_float3(1.f, -1.f, 1.f)); }, "HCPSampler::SampleBox");
    expectMsg([&] { grid.SampleBox(o, make_float3(nan)); }, "GridSampler::SampleBox");
    expectMsg([&] { hcp.SampleCylinderZ(o, -1.f, 1.f); }, "HCPSampler::SampleCylinderZ");
    expectMsg([&] { grid.SampleCylinderX(o, 1.f, -1.f); }, "GridSampler::SampleCylinderX");
    expectMsg([&] { hcp.SampleCylinderY(make_float3(inf, 0.f, 0.f), 1.f, 1.f); }, "HCPSampler::SampleCylinderY");
    expectMsg([&] { grid.SampleSphere(o, -0.5f); }, "GridSampler::SampleSphere");
    // Absurd size: refused before any allocation.
    expectMsg([&] { grid.SampleBox(o, make_float3(1e4f)); }, "GridSampler::SampleBox");
    expectMsg([&] { hcp.SampleSphere(o, 1e6f); }, "HCPSampler::SampleSphere");
}
