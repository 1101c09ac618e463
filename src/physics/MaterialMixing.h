// Effective contact moduli from the two sides' materials (Hertz theory):
//   1/E* = (1 - nuA^2)/EA + (1 - nuB^2)/EB,   1/G* = 2(2 - nuA)(1 + nuA)/EA + 2(2 - nuB)(1 + nuB)/EB.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

DEME_HD inline void matProxy2ContactParam(float& E_eff, float& G_eff, float EA, float nuA, float EB, float nuB) {
    E_eff = 1.f / ((1.f - nuA * nuA) / EA + (1.f - nuB * nuB) / EB);
    G_eff = 1.f / (2.f * (2.f - nuA) * (1.f + nuA) / EA + 2.f * (2.f - nuB) * (1.f + nuB) / EB);
}

// The damping term of a coefficient of restitution: beta = ln(CoR) / sqrt(ln^2(CoR) + pi^2), < 0.
// CoR = 0 is capped to keep the logarithm finite.
DEME_HD inline float dampingBetaFromCoR(float CoR) {
    const float logCoR = logf(CoR < 1e-12f ? 1e-12f : CoR);
    return logCoR / sqrtf(logCoR * logCoR + (float)PI * (float)PI);
}

// A pairwise material table indexed as table[matA][matB] from model code.
struct PairTable {
    const float* data;
    unsigned int n;
    DEME_HD const float* operator[](unsigned int i) const { return data + i * n; }
};

}  // namespace deme
