// Per-family rules: fixed, prescribed velocities (expressions of time) and the contact mask.
#pragma once

#include <array>
#include <vector>

#include <deme/VariableTypes.h>

#include "codegen/FamilyMotion.h"
#include "state/FamilyStepMotion.h"

namespace deme {

class FamilyRules {
  public:
    FamilyRules() : m_contactEnabled(NUM_FAMILIES * NUM_FAMILIES, 1) {}

    FamilyMotion& motion(unsigned int family) { return m_motion[family]; }
    const FamilyMotion& motion(unsigned int family) const { return m_motion[family]; }
    const std::array<FamilyMotion, NUM_FAMILIES>& motions() const { return m_motion; }
    void setContact(unsigned int a, unsigned int b, bool enabled) {
        m_contactEnabled[a * NUM_FAMILIES + b] = enabled;
        m_contactEnabled[b * NUM_FAMILIES + a] = enabled;
    }
    // 256 x 256 table: 1 where contacts between the two families are resolved.
    const uint8_t* contactMask() const { return m_contactEnabled.data(); }

    // Evaluates every family's prescription at time t.
    void evaluate(double t, std::array<FamilyStepMotion, NUM_FAMILIES>& out) const {
        for (unsigned int f = 0; f < NUM_FAMILIES; f++) {
            const FamilyMotion& m = m_motion[f];
            FamilyStepMotion& s = out[f];
            s = FamilyStepMotion();
            if (!m.hasAny()) continue;
            s.fixed = m.fixed;
            float lin[3] = {0.f, 0.f, 0.f}, ang[3] = {0.f, 0.f, 0.f};
            for (int i = 0; i < 3; i++) {
                if (m.linPrescribed[i]) {
                    s.linMask |= (uint8_t)(1u << i);
                    lin[i] = (float)m.lin[i].evaluate(&t);
                }
                if (m.angPrescribed[i]) {
                    s.angMask |= (uint8_t)(1u << i);
                    ang[i] = (float)m.ang[i].evaluate(&t);
                }
            }
            s.lin = make_float3(lin[0], lin[1], lin[2]);
            s.ang = make_float3(ang[0], ang[1], ang[2]);
        }
    }

  private:
    std::array<FamilyMotion, NUM_FAMILIES> m_motion;
    std::vector<uint8_t> m_contactEnabled;
};

}  // namespace deme
