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

import rolling_model

# Rolling: a spring on the relative rotation, its moment capped at Crr R |F_n|.
MODEL = rolling_model.hertz_mindlin(r"""
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
""", history=("m_roll_x", "m_roll_y", "m_roll_z"), stored=r"""
m_roll_x = m_roll.x;
m_roll_y = m_roll.y;
m_roll_z = m_roll.z;
""")


def use(sim):
    """Makes MODEL the solver's contact force model; returns it (not called for apart pairs, whose
    branch is the engine's rule for them: rolling_model.use)."""
    model = sim.DefineContactForceModel(MODEL)
    model.SetCalledForApartPairs(False)
    model.SetMustHaveMatProp(["E", "nu", "CoR"])
    model.SetMustPairwiseMatProp(["mu", "Crr", "CoR"])
    model.SetPerContactWildcards(["delta_tan_x", "delta_tan_y", "delta_tan_z", "delta_time", "m_roll_x", "m_roll_y",
                                  "m_roll_z"])
    return model
