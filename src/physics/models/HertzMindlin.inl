// Default contact force model: history-based Hertz-Mindlin with CoR-derived damping, Coulomb-capped
// Mindlin friction and rolling resistance as a torque-only force (paper §3.1).
// This file is a model *body*: it is compiled inside a function that defines the Table 3 variables
// (plus rotVelCPA/rotVelCPB, the global velocity of the contact point carried by each owner's spin,
// i.e. rotateToGlobal(AOriQ, cross(ARotVel, locCPA)) computed more cheaply),
// the material arrays E, nu (per material) and CoR, mu, Crr (per material pair), the derived pair
// tables E_eff, G_eff and beta_CoR (matProxy2ContactParam and dampingBetaFromCoR of those, mixed once
// per material pair rather than per contact: a logarithm and five divisions saved), the contact
// wildcards delta_tan_x/y/z and delta_time, and the outputs force and torque_only_force.

// Effective material parameters of this pair.
const float E_cnt = E_eff[bodyAMatType][bodyBMatType];
const float G_cnt = G_eff[bodyAMatType][bodyBMatType];
const float beta = beta_CoR[bodyAMatType][bodyBMatType];  // ln(CoR) / sqrt(ln^2(CoR) + pi^2) < 0
const float mu_cnt = mu[bodyAMatType][bodyBMatType];
const float Crr_cnt = Crr[bodyAMatType][bodyBMatType];

// Relative velocity of A's material point with respect to B's; its normal part is positive when separating.
const float3 velB2A = (ALinVel + rotVelCPA) - (BLinVel + rotVelCPB);
const float vn = dot(velB2A, B2A);
const float3 vrel_tan = velB2A - vn * B2A;

// Tangential micro-displacement: accumulate, then keep it in the current tangent plane.
float3 delta_tan = make_float3(delta_tan_x, delta_tan_y, delta_tan_z);
delta_tan += ts * vrel_tan;
delta_tan -= dot(delta_tan, B2A) * B2A;
delta_time += ts;

const float mass_eff = (AOwnerMass * BOwnerMass) / (AOwnerMass + BOwnerMass);
const float R_eff = (ARadius * BRadius) / (ARadius + BRadius);
const float sqrt_Rd = sqrtf(R_eff * (float)overlapDepth);

// Normal force: Hertz spring k_n * delta (k_n = 4/3 E* sqrt(R delta)) and viscous damping.
const float Sn = 2.f * E_cnt * sqrt_Rd;
const float k_n = 2.f / 3.f * Sn;
const float gamma_n = 2.f * sqrtf(5.f / 6.f) * beta * sqrtf(Sn * mass_eff);
force += (k_n * (float)overlapDepth + gamma_n * vn) * B2A;

// Rolling resistance, applied only once the contact has outlived one collision time, so that
// impacts are not slowed by it.
if (Crr_cnt > 0.f) {
    const float kn_simple = 4.f / 3.f * E_cnt * sqrtf(R_eff);
    const float gn_simple = -2.f * sqrtf(5.f / 3.f * mass_eff * E_cnt) * beta * powf(R_eff, 0.25f);
    const float d_coeff = gn_simple / (2.f * sqrtf(kn_simple * mass_eff));
    bool resting_contact = true;
    if (d_coeff < 1.f) {
        const float t_collision = (float)deme::PI * sqrtf(mass_eff / (kn_simple * (1.f - d_coeff * d_coeff)));
        resting_contact = delta_time > t_collision;
    }
    if (resting_contact) {
        // Direction of B's rolling-induced motion relative to A at the contact point.
        const float3 v_rot = rotVelCPB - rotVelCPA;
        const float v_rot_mag = length(v_rot);
        if (v_rot_mag > 1e-12f) torque_only_force = (v_rot / v_rot_mag) * (Crr_cnt * length(force));
    }
}

// Mindlin friction with a Coulomb cap; at the cap the stored displacement is rescaled so that it
// reproduces the capped force.
if (mu_cnt > 0.f) {
    const float k_t = 8.f * G_cnt * sqrt_Rd;
    const float gamma_t = -2.f * sqrtf(5.f / 6.f) * beta * sqrtf(mass_eff * k_t);
    float3 tangent_force = -k_t * delta_tan - gamma_t * vrel_tan;
    const float ft = length(tangent_force);
    if (ft > 1e-12f) {
        const float ft_max = length(force) * mu_cnt;
        if (ft > ft_max) {
            tangent_force = (ft_max / ft) * tangent_force;
            delta_tan = (tangent_force + gamma_t * vrel_tan) / (-k_t);
        }
    } else {
        tangent_force = make_float3(0.f, 0.f, 0.f);
    }
    force += tangent_force;
}

delta_tan_x = delta_tan.x;
delta_tan_y = delta_tan.y;
delta_tan_z = delta_tan.z;
