// The built-in force model compiled statically for the CPU: it defines the variables that model
// bodies refer to and includes the default model body, the same text a GPU build compiles at run time.
#pragma once

#include "ContactInputs.h"
#include "MaterialMixing.h"
#include "Quaternion.h"

namespace deme {

// Material tables the default model reads: per pair mu and Crr and the derived E_eff, G_eff and
// beta_CoR (see MaterialTables).
struct DefaultModelMaterials {
    PairTable mu, Crr, E_eff, G_eff, beta_CoR;
};

// Number and order of the default model's per-contact wildcards.
constexpr unsigned int DEFAULT_MODEL_NUM_WILDCARDS = 4;  // delta_tan_x, delta_tan_y, delta_tan_z, delta_time

DEME_HD_INLINE void defaultForceModel(const ContactInputs& in, const DefaultModelMaterials& mat, float* wildcards,
                                      float3& force, float3& torque_only_force) {
    const double3 contactPnt = in.contactPnt;
    const float3 B2A = in.B2A;
    const double overlapDepth = in.overlapDepth;
    const float ts = in.ts;
    const float3 rotVelCPA = in.rotVelCPA, rotVelCPB = in.rotVelCPB;
    const float AOwnerMass = in.AOwnerMass, BOwnerMass = in.BOwnerMass;
    const float ARadius = in.ARadius, BRadius = in.BRadius;
    const materialID_t bodyAMatType = in.bodyAMatType, bodyBMatType = in.bodyBMatType;
    const float3 ALinVel = in.ALinVel, BLinVel = in.BLinVel;
    const PairTable mu = mat.mu, Crr = mat.Crr, E_eff = mat.E_eff, G_eff = mat.G_eff, beta_CoR = mat.beta_CoR;
    float& delta_tan_x = wildcards[0];
    float& delta_tan_y = wildcards[1];
    float& delta_tan_z = wildcards[2];
    float& delta_time = wildcards[3];
    (void)contactPnt;
#include "models/HertzMindlin.inl"
}

}  // namespace deme
