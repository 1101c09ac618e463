// Per-family rules: fixed, prescribed velocities (expressions of time) and the contact mask.
#pragma once

#include <array>
#include <vector>

#include <deme/VariableTypes.h>

#include "codegen/FamilyCondition.h"
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
    // Family changes on conditions (ChangeFamilyWhen), checked in this order at each detection.
    std::vector<FamilyCondition>& conditions() { return m_conditions; }
    const std::vector<FamilyCondition>& conditions() const { return m_conditions; }
    // Whether some family is fixed: only then can an owner be at rest (dynamics/OwnerStep.h, ownerAtRest).
    bool anyFixed() const {
        for (const FamilyMotion& m : m_motion)
            if (m.fixed) return true;
        return false;
    }
    // Families whose owners are dormant: fixed, and with contacts disabled with every fixed family
    // (itself included), so that their pairs among each other never need detecting. 1 per family.
    // And 1 per family with a prescribed velocity component: its owners move.
    void prescribedFamilies(uint8_t* out) const {
        for (unsigned int f = 0; f < NUM_FAMILIES; f++) {
            const FamilyMotion& m = m_motion[f];
            out[f] = !m.fixed && (m.linPrescribed[0] || m.linPrescribed[1] || m.linPrescribed[2] ||
                                  m.angPrescribed[0] || m.angPrescribed[1] || m.angPrescribed[2]);
        }
    }
    void dormantFamilies(uint8_t* out) const {
        for (unsigned int f = 0; f < NUM_FAMILIES; f++) {
            out[f] = m_motion[f].fixed ? 1 : 0;
            for (unsigned int g = 0; g < NUM_FAMILIES && out[f]; g++)
                if (m_motion[g].fixed && m_contactEnabled[f * NUM_FAMILIES + g]) out[f] = 0;
        }
    }

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
    std::vector<FamilyCondition> m_conditions;
};

}  // namespace deme
