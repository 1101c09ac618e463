// Small helpers shared by the validation tests.
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <deme/deme.h>

namespace deme_test {

using namespace deme;

inline std::map<std::string, double> material(double E, double nu, double CoR, double mu, double Crr = 0.0) {
    return {{"E", E}, {"nu", nu}, {"CoR", CoR}, {"mu", mu}, {"Crr", Crr}};
}

inline double sphereMass(double r, double density) { return density * 4.0 / 3.0 * deme::PI * r * r * r; }

// Effective modulus of two identical materials: E* = E / (2 (1 - nu^2)).
inline double effectiveModulus(double E, double nu) { return E / (2.0 * (1.0 - nu * nu)); }

// 1,000 spheres of r = 4 mm (2,500 kg/m^3) on a lattice 9.5 mm apart (8.5 mm in z) in a closed
// 0.1 x 0.1 x 0.2 m box, under gravity, dt 2e-5 s, not yet initialized: settled after 0.3 s, each
// touches about six others. The memory tests' scene. With `sideways` > 0, each sphere is shifted in
// x and y by up to that much (a fixed sequence), so that the bed they fall into is disordered and
// its contacts push sideways too. Returns the spheres' batch.
inline std::shared_ptr<DEMClumpBatch> addThousandSphereBed(DEMSolver& sim, float sideways = 0.f) {
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.4));
    sim.InstructBoxDomainDimension({0.f, 0.1f}, {0.f, 0.1f}, {0.f, 0.2f});
    sim.InstructBoxDomainBoundingBC("all", mat);
    const float r = 0.004f;
    auto type = sim.LoadSphereType((float)sphereMass(r, 2500), r, mat);
    unsigned int seed = 12345u;
    auto shift = [&seed, sideways] {
        seed = seed * 1664525u + 1013904223u;
        return sideways * ((float)(seed >> 8) / 8388608.f - 1.f);
    };
    std::vector<float3> xyz;
    for (int k = 0; k < 10; k++)
        for (int j = 0; j < 10; j++)
            for (int i = 0; i < 10; i++) {
                const float dx = shift(), dy = shift();
                xyz.push_back(make_float3(0.007f + 0.0095f * i + dx, 0.007f + 0.0095f * j + dy, 0.006f + 0.0085f * k));
            }
    auto batch = sim.AddClumps(type, xyz);
    sim.SetInitTimeStep(2e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    return batch;
}

// The message of the deme::Error that f throws; fails the test if it throws none.
template <class F>
std::string demeErrorMessage(F&& f) {
    try {
        f();
    } catch (const deme::Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no deme::Error thrown";
    return "";
}

// How many step batches ended early (a set that expired, a fault), from the collaboration report.
inline unsigned long long batchesEndedEarly(const deme::DEMSolver& sim) {
    testing::internal::CaptureStdout();
    sim.ShowThreadCollaborationStats();
    const std::string report = testing::internal::GetCapturedStdout();
    const std::string tail = " ended early";
    const size_t at = report.find(tail);
    if (at == std::string::npos) return 0;
    const size_t start = report.rfind(", ", at);
    return std::stoull(report.substr(start + 2, at - start - 2));
}

}  // namespace deme_test
