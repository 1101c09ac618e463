// The built-in contact force models, compiled statically into the library (no compiler is needed at
// run time for them). Each is a functor of the shape the force loop expects (backend/cpu/ForcePassLoop.h):
// it defines, as local variables, the inputs its model body refers to and includes that body, the
// same text a user could hand to DefineContactForceModel (docs/force-models.md).
#pragma once

#include "ContactInputs.h"
#include "MaterialMixing.h"
#include "Quaternion.h"

namespace deme {

// The default model (paper §3.1): history-based Hertz-Mindlin with CoR-derived damping, Coulomb-capped
// friction and rolling resistance. Contact wildcards, in this order: delta_tan_x, delta_tan_y,
// delta_tan_z, delta_time.
struct FrictionalHertzModel {
    static constexpr unsigned int kNumContactWildcards = 4;
    static constexpr bool kSeesApartPairs = false;
    static constexpr bool kWritesPersistent = false;
    static constexpr bool kWritesCouple = false;

    // Pair tables: mu and Crr, and the derived E_eff, G_eff and beta_CoR (see MaterialTables).
    PairTable mu, Crr, E_eff, G_eff, beta_CoR;

    DEME_HD_INLINE void operator()(const ContactInputs& in, float* contactWildcards, float3& force,
                                   float3& torque_only_force, float3& couple_torque, bool& persistent) const {
        (void)couple_torque;
        (void)persistent;
        const float3 B2A = in.B2A;
        const double overlapDepth = in.overlapDepth;
        const float ts = in.ts;
        const float3 rotVelCPA = in.rotVelCPA, rotVelCPB = in.rotVelCPB;
        const float AOwnerMass = in.AOwnerMass, BOwnerMass = in.BOwnerMass;
        const float ARadius = in.ARadius, BRadius = in.BRadius;
        const materialID_t bodyAMatType = in.bodyAMatType, bodyBMatType = in.bodyBMatType;
        const float3 ALinVel = in.ALinVel, BLinVel = in.BLinVel;
        float& delta_tan_x = contactWildcards[0];
        float& delta_tan_y = contactWildcards[1];
        float& delta_tan_z = contactWildcards[2];
        float& delta_time = contactWildcards[3];
#include "models/HertzMindlin.inl"
    }
};

// Hertzian normal force with CoR-derived damping only: no friction, no rolling resistance, no
// contact wildcards.
struct FrictionlessHertzModel {
    static constexpr unsigned int kNumContactWildcards = 0;
    static constexpr bool kSeesApartPairs = false;
    static constexpr bool kWritesPersistent = false;
    static constexpr bool kWritesCouple = false;

    PairTable E_eff, beta_CoR;

    DEME_HD_INLINE void operator()(const ContactInputs& in, float* contactWildcards, float3& force,
                                   float3& torque_only_force, float3& couple_torque, bool& persistent) const {
        (void)contactWildcards;
        (void)torque_only_force;
        (void)couple_torque;
        (void)persistent;
        const float3 B2A = in.B2A;
        const double overlapDepth = in.overlapDepth;
        const float3 rotVelCPA = in.rotVelCPA, rotVelCPB = in.rotVelCPB;
        const float AOwnerMass = in.AOwnerMass, BOwnerMass = in.BOwnerMass;
        const float ARadius = in.ARadius, BRadius = in.BRadius;
        const materialID_t bodyAMatType = in.bodyAMatType, bodyBMatType = in.bodyBMatType;
        const float3 ALinVel = in.ALinVel, BLinVel = in.BLinVel;
#include "models/HertzFrictionless.inl"
    }
};

}  // namespace deme
