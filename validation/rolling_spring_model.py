"""Hertz-Mindlin with an elastic-plastic rolling resistance: the default model (src/physics/models/
HertzMindlin.inl, paper s. 3.1) with its rolling term replaced by a rolling spring whose moment is
capped at the default model's rolling moment, so that a contact below its cap holds still (a static
state) instead of flipping a constant moment every step. This is the elastic-plastic spring of Ai,
Chen, Rotter & Ooi (2011, Powder Technol. 206, 269; their model C without its damper):

    M += -k_r (w_A - w_B) dt, its part along the normal removed;  |M| <= Crr R |F_n|,
    k_r = k_t R^2,  R = the smaller radius (a sphere's own against a wall),

stored per contact and applied as a pure couple (`couple_torque`: +M on A, -M on B). The cap is the
paper's rolling moment, Crr |F_n| times the contact's arm, so where a contact rolls the two models
brake alike; they differ only where the default model's moment would flip.

Contact wildcards: delta_tan_x/y/z (the tangential displacement), delta_time (the contact's age) and
m_roll_x/y/z (the rolling moment). Pair properties: mu, Crr, CoR; per material E, nu, CoR.
"""

MODEL = r"""
if (overlapDepth <= 0.0) {
    delta_tan_x = 0.f; delta_tan_y = 0.f; delta_tan_z = 0.f; delta_time = 0.f;
    m_roll_x = 0.f; m_roll_y = 0.f; m_roll_z = 0.f;
    return;
}
const float E_cnt = E_eff[bodyAMatType][bodyBMatType];
const float G_cnt = G_eff[bodyAMatType][bodyBMatType];
const float beta = beta_CoR[bodyAMatType][bodyBMatType];
const float mu_cnt = mu[bodyAMatType][bodyBMatType];
const float Crr_cnt = Crr[bodyAMatType][bodyBMatType];

const float3 velB2A = (ALinVel + rotVelCPA) - (BLinVel + rotVelCPB);
const float vn = dot(velB2A, B2A);
const float3 vrel_tan = velB2A - vn * B2A;
float3 delta_tan = make_float3(delta_tan_x, delta_tan_y, delta_tan_z);
delta_tan += ts * vrel_tan;
delta_tan -= dot(delta_tan, B2A) * B2A;
delta_time += ts;

const float mass_eff = (AOwnerMass * BOwnerMass) / (AOwnerMass + BOwnerMass);
const float R_eff = (ARadius * BRadius) / (ARadius + BRadius);
const float sqrt_Rd = sqrtf(R_eff * (float)overlapDepth);
const float Sn = 2.f * E_cnt * sqrt_Rd;
const float k_n = 2.f / 3.f * Sn;
const float gamma_n = 2.f * sqrtf(5.f / 6.f) * beta * sqrtf(Sn * mass_eff);
force += (k_n * (float)overlapDepth + gamma_n * vn) * B2A;
const float k_t = 8.f * G_cnt * sqrt_Rd;

// Rolling: a spring on the relative rotation, its moment capped at Crr R |F_n|.
float3 m_roll = make_float3(m_roll_x, m_roll_y, m_roll_z);
if (Crr_cnt > 0.f) {
    const float R_roll = ARadius < BRadius ? ARadius : BRadius;
    const float3 w_rel = rotateToGlobal(AOriQ, ARotVel) - rotateToGlobal(BOriQ, BRotVel);
    m_roll -= (k_t * R_roll * R_roll * ts) * w_rel;
    m_roll -= dot(m_roll, B2A) * B2A;
    const float m_mag = length(m_roll);
    const float m_max = Crr_cnt * R_roll * length(force);
    if (m_mag > m_max) m_roll = (m_max / m_mag) * m_roll;
    couple_torque = m_roll;
}

if (mu_cnt > 0.f) {
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
m_roll_x = m_roll.x;
m_roll_y = m_roll.y;
m_roll_z = m_roll.z;
"""


def use(sim):
    """Makes MODEL the solver's contact force model; returns it."""
    model = sim.DefineContactForceModel(MODEL)
    model.SetMustHaveMatProp(["E", "nu", "CoR"])
    model.SetMustPairwiseMatProp(["mu", "Crr", "CoR"])
    model.SetPerContactWildcards(["delta_tan_x", "delta_tan_y", "delta_tan_z", "delta_time", "m_roll_x", "m_roll_y",
                                  "m_roll_z"])
    return model
