"""The default contact model (src/physics/models/HertzMindlin.inl, paper s. 3.1) written as a custom
model, with its friction and rolling caps taken from the whole normal force (`CAPS = "total"`, the
default's form: the stacking study checks that it gives the default's ladders exactly) or from its
elastic part alone (`"elastic"`, k_n delta, the viscous part left out), for the stacking case's study
of the damping (validation/README.md, "Three-sphere stacking"). Rolling: the default's force
Crr |cap| along the spin part of the surfaces' sliding velocity, applied at the contact point
(`torque_only_force`), without the default's wait of one collision time (the stacks' contacts are
long-lived). Contact wildcards: delta_tan_x/y/z, delta_time."""

import rolling_model


def model_text(caps):
    cap = {"total": "length(force)", "elastic": "(k_n * (float)overlapDepth)"}[caps]
    text = rolling_model.hertz_mindlin(r"""
if (Crr_cnt > 0.f) {
    const float3 v_rot = rotVelCPB - rotVelCPA;
    const float v_rot_mag = length(v_rot);
    if (v_rot_mag > 1e-12f) torque_only_force = (v_rot / v_rot_mag) * (Crr_cnt * CAP);
}
""".replace("CAP", cap))
    friction_cap = "const float ft_max = length(force) * mu_cnt;"
    assert friction_cap in text
    return text.replace(friction_cap, f"const float ft_max = {cap} * mu_cnt;")


def use(sim, caps):
    """Makes the model with the given caps ("total" or "elastic") the solver's; returns it."""
    return rolling_model.use(sim, model_text(caps))
