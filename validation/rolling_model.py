"""Hertz-Mindlin with a rolling resistance that opposes the owners' relative spin: the default model
(src/physics/models/HertzMindlin.inl, paper s. 3.1) with its rolling term replaced by the constant
directional torque of Ai, Chen, Rotter & Ooi (2011, Powder Technol. 206, 269; their model A), which is
LIGGGHTS 3.8's `rolling_friction cdt`:

    tau_A = -Crr R_eff k_n delta (w_rel / |w_rel|), minus its part along the normal; tau_B = -tau_A,
    w_rel = w_A - w_B (global), R_eff = R_A R_B / (R_A + R_B) (R_A against a wall),

applied as a pure couple (`couple_torque`). Why not the paper's form, F_r = Crr |F_n| along
w_B x r_B - w_A x r_A at the contact point, applied as a force pair there (`torque_only_force`):
that form is the spin part of the surfaces' sliding velocity, not their rolling. Two grains rolling
over each other without sliding (spins of opposite sense) feel none of it, two grains turning together
as one body (the same spin) are braked, and both get torques of the same sense; a sphere carried round
by a turning wall is braked as if it rolled on it. Against a wall at rest, where the paper's
incline and stacking tests put it, the two forms are the same. In the rotating drum at mu = 0 the
paper's form holds the spheres' surface at 15 degrees (Crr = 0.04 and 0.08, grain-wall mu 0.3), where
frictionless grains lie flat: locked spins turn the walls' friction into drag (validation/README.md).

Contact wildcards: delta_tan_x, delta_tan_y, delta_tan_z (the tangential displacement) and delta_time
(the contact's age), as the default model's. Pair properties: mu, Crr and CoR (SetMustPairwiseMatProp);
per material: E, nu, CoR (through the derived tables E_eff, G_eff, beta_CoR).
"""

def hertz_mindlin(rolling, history=(), stored=""):
    """The default model's body (Hertz normal force with CoR damping, Mindlin friction capped at mu
    |F_n|) with `rolling` as its rolling term: C++ run after the normal force, with k_n, k_t, R_eff,
    overlapDepth and the normal force in `force` defined; `history` names the rolling term's own
    contact wildcards (cleared when the pair is apart), `stored` writes them back at the end."""
    clear = "".join(f" {w} = 0.f;" for w in history)
    return r"""
if (overlapDepth <= 0.0) {
    // Apart: no force, and the history ends (the default model is not called for such pairs).
    delta_tan_x = 0.f; delta_tan_y = 0.f; delta_tan_z = 0.f; delta_time = 0.f;""" + clear + r"""
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
""" + rolling + r"""
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
""" + stored


# Rolling resistance: a couple against the relative spin, of size Crr R_eff times the elastic normal
# force, its twisting part removed.
MODEL = hertz_mindlin(r"""
if (Crr_cnt > 0.f) {
    const float3 w_rel = rotateToGlobal(AOriQ, ARotVel) - rotateToGlobal(BOriQ, BRotVel);
    const float w_mag = length(w_rel);
    if (w_mag > 1e-12f) {
        float3 tau = (-Crr_cnt * R_eff * k_n * (float)overlapDepth / w_mag) * w_rel;
        tau -= dot(tau, B2A) * B2A;
        couple_torque = tau;
    }
}
""")


def use(sim, text=MODEL, called_for_apart_pairs=False):
    """Makes MODEL (or another text of hertz_mindlin's, with its wildcards) the solver's contact force
    model; returns it. hertz_mindlin's branch for pairs that are apart (no force, history cleared) is
    what the engine does for a model not called for them (SetCalledForApartPairs(False)), which then
    skips them before gathering their inputs: the same results, faster (most of a contact set's pairs
    are apart); called_for_apart_pairs=True runs that branch instead, for comparison."""
    model = sim.DefineContactForceModel(text)
    model.SetCalledForApartPairs(called_for_apart_pairs)
    model.SetMustHaveMatProp(["E", "nu", "CoR"])
    model.SetMustPairwiseMatProp(["mu", "Crr", "CoR"])  # CoR: beta_CoR mixes the pair values
    model.SetPerContactWildcards(["delta_tan_x", "delta_tan_y", "delta_tan_z", "delta_time"])
    return model
