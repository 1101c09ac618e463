// Small helpers for setting up simulations.
#pragma once

#include <cmath>

#include "VariableTypes.h"

namespace deme {

// Rayleigh time of a sphere of radius r: the time a Rayleigh surface wave takes to cross it. Explicit
// DEM time steps are usually chosen as 5-20 % of it.
inline double RayleighTime(double r, double density, double E, double nu) {
    const double G = E / (2.0 * (1.0 + nu));
    return PI * r * std::sqrt(density / G) / (0.1631 * nu + 0.8766);
}

}  // namespace deme
