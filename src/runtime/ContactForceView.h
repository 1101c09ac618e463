// Per-contact forces (on A, global) as readers see them, by contact index, whichever backend ran the
// steps: a GPU run's host copy holds them per contact (downloaded with the set); the CPU keeps those
// of its last storing step for the pairs with a force only (ContactArrays::stored), which the view
// spreads over the set for as long as the reader holds it. Pairs without a stored force, and
// every pair before a step has stored (a set just installed), read as zero.
#pragma once

#include <vector>

#include "state/SimState.h"

namespace deme {

class ContactForceView {
  public:
    explicit ContactForceView(const ContactArrays& c) {
        const size_t n = c.size();
        if (c.force.size() == n) {
            m_forces = c.force.data();
            return;
        }
        m_spread.assign(n, make_float3(0.f));
        const StoredContactForces& st = c.stored;
        for (size_t t = 0; t < st.index.size(); t++)
            for (size_t k = 0; k < st.index[t].size(); k++) m_spread[st.index[t][k]] = st.force[t][k];
        m_forces = m_spread.data();
    }
    float3 operator[](size_t i) const { return m_forces[i]; }

  private:
    const float3* m_forces = nullptr;
    std::vector<float3> m_spread;
};

}  // namespace deme
