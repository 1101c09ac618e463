// The stress of the grains measured from the state after a step (include/deme/Stress.h has the
// formula): one region, or a grid of cells over a box (the coarse-grained field that
// WriteStressField writes). Host code over the host state; per-contact forces are those the last
// step stored (both backends store them in the last step of a call).
#pragma once

#include <vector>

#include <deme/Stress.h>

#include "state/SimState.h"

namespace deme {

// Cells of a box [lo, hi] split into n[0] x n[1] x n[2] (x fastest); one sample per cell.
std::vector<StressTensor> measureStressField(const SimState& s, const double3& lo, const double3& hi,
                                             const unsigned int n[3]);

inline StressTensor measureStress(const SimState& s, const double3& lo, const double3& hi) {
    const unsigned int one[3] = {1, 1, 1};
    return measureStressField(s, lo, hi, one)[0];
}

}  // namespace deme
