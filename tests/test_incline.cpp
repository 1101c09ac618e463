// The paper's §3.3.1 incline test (after Fleischmann et al. / Zhang et al. 2021): a sphere of
// r = 0.2 m, m = 5 kg, mu = 0.25 starts at 0.5 m/s up an incline of angle alpha. Its end state is
//   stationary            if alpha <= atan(Crr),
//   pure rolling          if atan(Crr) < alpha <= atan(3.5 mu - 2.5 Crr),
//   rolling with sliding  otherwise.
// The incline is the plane z = 0 with gravity tilted by alpha; we check a grid of (alpha, Crr)
// that keeps at least 2 degrees from either boundary line.
#include <gtest/gtest.h>

#include <cmath>

#include "BackendFixture.h"
#include "RollingSphere.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(Incline);

namespace {

enum class EndState { STATIONARY, ROLLING, SLIDING };

const char* name(EndState s) {
    return s == EndState::STATIONARY ? "stationary" : s == EndState::ROLLING ? "rolling" : "sliding";
}

EndState theory(double alphaDeg, double mu, double crr) {
    const double a = alphaDeg * deme::PI / 180.0;
    if (a <= std::atan(crr)) return EndState::STATIONARY;
    if (a <= std::atan(3.5 * mu - 2.5 * crr)) return EndState::ROLLING;
    return EndState::SLIDING;
}

EndState simulate(double alphaDeg, double mu, double crr) {
    const double r = 0.2, m = 5.0, g = 9.81, a = alphaDeg * deme::PI / 180.0;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, mu, crr));
    sim.InstructBoxDomainDimension(80, 4, 4);
    sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    auto tmpl = sim.LoadSphereType((float)m, (float)r, mat);
    // Start resting on the plane (static Hertz overlap), moving up the slope (+x).
    const double Estar = effectiveModulus(1e7, 0.3);
    const double overlap = std::pow(m * g * std::cos(a) / (4.0 / 3.0 * Estar * std::sqrt(r)), 2.0 / 3.0);
    auto ball = sim.AddClumps(tmpl, {make_float3(30.f, 0, (float)(r - overlap))});
    ball->SetVel(make_float3(0.5f, 0, 0));
    sim.SetInitTimeStep(1e-4);
    // Down the slope is -x.
    sim.SetGravitationalAcceleration(make_float3((float)(-g * std::sin(a)), 0, (float)(-g * std::cos(a))));
    sim.Initialize();
    auto tr = sim.Track(ball);
    sim.DoDynamics(2.0);
    const double v = tr->Vel().x;          // along the slope
    const double w = tr->AngVelLocal().y;  // rolling down (-x) turns about -y: w < 0, v = w r
    const double slip = v - w * r;         // velocity of the contact point
    if (std::fabs(v) < 1e-3 && std::fabs(w * r) < 1e-3) return EndState::STATIONARY;
    if (std::fabs(slip) < 0.01 * std::fabs(v)) return EndState::ROLLING;
    return EndState::SLIDING;
}

}  // namespace

DEME_BACKEND_TEST(Incline, EndStateMatchesTheoryBoundaries) {
    const double mu = 0.25;
    int checked = 0;
    for (double crr : {0.0, 0.05, 0.1, 0.2}) {
        for (double alpha : {2.0, 8.0, 15.0, 25.0, 35.0, 45.0}) {
            const double d1 = std::fabs(alpha - std::atan(crr) * 180.0 / deme::PI);
            const double d2 = std::fabs(alpha - std::atan(3.5 * mu - 2.5 * crr) * 180.0 / deme::PI);
            if (d1 < 2.0 || d2 < 2.0) continue;  // too close to a boundary line
            const EndState expected = theory(alpha, mu, crr);
            const EndState got = simulate(alpha, mu, crr);
            EXPECT_EQ(got, expected) << "alpha " << alpha << " deg, Crr " << crr << ": expected " << name(expected)
                                     << ", got " << name(got);
            checked++;
        }
    }
    EXPECT_GE(checked, 18);
}

// The rolling regime in numbers: a sphere rolling without slip up a 10 degree incline decelerates at
// (5/7) g sin(alpha) (solid sphere, I = 2/5 m r^2); after 0.5 s its velocity is within 0.5 % of
// v0 - (5/7) g sin(alpha) t. (GpuParity.RollingSphereOnIncline compares the backends to 1e-4.)
DEME_BACKEND_TEST(Incline, RollingSphereDeceleratesAtFiveSeventhsGSinAlpha) {
    const double expected = RollingSphere::theory();
    EXPECT_NEAR(RollingSphere::velocityAfterRun(backend()), expected, 0.005 * expected);
}
