// The paper's user-referable variables (Table 3) for one contact, gathered by the force pass and
// handed to a contact force model. Model code sees each member as a local variable of that name.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

struct ContactInputs {
    double3 contactPnt;     // contact point, global
    float3 B2A;             // unit normal from geometry B to geometry A
    double overlapDepth;    // penetration (negative: apart)
    float ts;               // time step
    float time;             // simulation time
    float3 locCPA, locCPB;  // contact point in the owners' local frames (relative to the owner centre)
    double3 AOwnerPos, BOwnerPos;
    double3 bodyAPos, bodyBPos;  // positions of the contact geometries
    float4 AOriQ, BOriQ;
    float AOwnerMass, BOwnerMass;
    float3 AOwnerMOI, BOwnerMOI;
    float ARadius, BRadius;  // curvature radii at the contact
    materialID_t bodyAMatType, bodyBMatType;
    family_t AOwnerFamily, BOwnerFamily;
    float3 ALinVel, BLinVel;  // owner velocities, global
    float3 ARotVel, BRotVel;  // owner angular velocities, local frames
    bodyID_t AOwner, BOwner;
    bodyID_t AGeo, BGeo;
    // Beyond Table 3, cheaper forms of the same kinematics, in the global frame:
    float3 armA, armB;            // contact point minus each owner's centre
    float3 rotVelCPA, rotVelCPB;  // velocity of the contact point carried by each owner's spin
};

}  // namespace deme
