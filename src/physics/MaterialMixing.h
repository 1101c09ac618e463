// Effective contact moduli from the two sides' materials (Hertz theory):
//   1/E* = (1 - nuA^2)/EA + (1 - nuB^2)/EB,   1/G* = 2(2 - nuA)(1 + nuA)/EA + 2(2 - nuB)(1 + nuB)/EB.
#pragma once

#include <deme/VectorTypes.h>

namespace deme {

DEME_HD inline void matProxy2ContactParam(float& E_eff, float& G_eff, float EA, float nuA, float EB, float nuB) {
    E_eff = 1.f / ((1.f - nuA * nuA) / EA + (1.f - nuB * nuB) / EB);
    G_eff = 1.f / (2.f * (2.f - nuA) * (1.f + nuA) / EA + 2.f * (2.f - nuB) * (1.f + nuB) / EB);
}

// A pairwise material table indexed as table[matA][matB] from model code.
struct PairTable {
    const float* data;
    unsigned int n;
    DEME_HD const float* operator[](unsigned int i) const { return data + i * n; }
};

}  // namespace deme
