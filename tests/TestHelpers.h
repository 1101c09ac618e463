// Small helpers shared by the validation tests.
#pragma once

#include <cmath>
#include <map>
#include <string>

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

}  // namespace deme_test
