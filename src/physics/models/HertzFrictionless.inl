// Frictionless Hertzian contact force model: the normal part of the default model
// (HertzMindlin.inl), a Hertz spring with CoR-derived viscous damping, and nothing tangential.
// A model *body* like HertzMindlin.inl: compiled inside a function that defines B2A, overlapDepth,
// the owner masses, radii, velocities, rotVelCPA/rotVelCPB, bodyAMatType/bodyBMatType, the pair tables
// E_eff and beta_CoR, and the output force.

const float E_cnt = E_eff[bodyAMatType][bodyBMatType];
const float beta = beta_CoR[bodyAMatType][bodyBMatType];  // ln(CoR) / sqrt(ln^2(CoR) + pi^2) < 0

// Normal part of the relative velocity of A's material point with respect to B's (positive when separating).
const float vn = dot((ALinVel + rotVelCPA) - (BLinVel + rotVelCPB), B2A);

const float mass_eff = (AOwnerMass * BOwnerMass) / (AOwnerMass + BOwnerMass);
const float R_eff = (ARadius * BRadius) / (ARadius + BRadius);
const float Sn = 2.f * E_cnt * sqrtf(R_eff * (float)overlapDepth);
const float k_n = 2.f / 3.f * Sn;
const float gamma_n = 2.f * sqrtf(5.f / 6.f) * beta * sqrtf(Sn * mass_eff);
force += (k_n * (float)overlapDepth + gamma_n * vn) * B2A;
