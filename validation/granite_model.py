"""The bonded granite of the paper's s. 6.4: Scholtes & Donze's (2013) cohesive-frictional bond law as a
custom contact force model, and the uniaxial compression rig it is tested in (validation/cases/granite.py).

The law (paper s. 6.4, after Scholtes & Donze 2013, Int. J. Rock Mech. Min. Sci. 61:101-111):
- Bonds link a sphere to the neighbours whose surfaces lie within gamma_int * R of its own when the
  specimen is made (R the smaller radius); they are the only links that carry tension.
- Normal force F_n = k_n u_n - gamma_n m* v_n, u_n the overlap change since bonding (compression
  positive), k_n = 2 E_micro R_i R_j / (R_i + R_j), gamma_n = 0.01 sqrt(k_n / m*) (paper's Eq.).
  In tension the bond yields at u_n = delta_y = -sigma_t A_int / k_n and softens linearly with the
  stiffness -k_n / xi, xi = 2, down to zero force at delta_b = 3 delta_y, where it breaks (the
  paper's three cases of k_n, written so that the force is continuous at delta_y).
- Tangential force F_t = -k_t u_t - gamma_t m* v_t, k_t = nu k_n, u_t the tangential displacement
  (incremental, rotated into the current tangent plane), capped by mu |F_n| + c A_int while the bond
  has not yielded and by mu |F_n| after; a bond whose shear force exceeds its cap breaks.
- A_int = pi min(R_i, R_j)^2; sigma_t = 9.3 MPa and c = 200 MPa (the paper's listing), mu = 0.3.
- A broken or never-bonded pair in contact follows Hertz-Mindlin (paper s. 3.1: E_eff, G_eff from
  E and nu, CoR-derived damping, Coulomb friction with mu of the pair); so do the spheres and plates.
- The bending moment (the paper's s. 6.4, after Belheine et al. 2009): a rotational spring of stiffness
  k_r = R_i R_j k_t on the two spheres' relative rolling (their relative spin less its twisting part,
  integrated incrementally and kept in the contact's tangent plane), capped at eta min(R_i, R_j) |F_n|
  with eta = 0.1 in the paper's listing, with no failure of its own, on bonds and unbonded sphere
  pairs alike (not on the plates). It acts as a pure couple (`couple_torque`: A gets it, B its
  opposite), as a bent bond's moment does; the paper's listing
  adds to the contact force a force min(ts k_r / R_A, eta |F|) along a rotational velocity instead,
  which is neither a couple nor a spring's moment (and about 2 mN here, against a bond's yield force
  of 42 N: practically none), so we follow its text, not its listing, where the moment is applied
  (GRANITE_ETA=0.1); by default it is left out (eta = 0), as it practically was in the paper's runs.

Each sphere's owner wildcard `cracked` turns 1 when one of its bonds breaks (for the rendering).
"""
import math
import os

import numpy as np

def _bending(kt, fn):
    """The bending moment's step in the model's text (the spring k_r = R_i R_j k_t, capped at eta min(R)
    |F_n|), given the branch's k_t and |F_n|: written once, put in both branches."""
    return f"""if (etaR > 0.f) {{
    mr -= ts * ARadius * BRadius * {kt} * wRoll;
    const float mCap = etaR * rMin * {fn}, mLen = length(mr);
    if (mLen > mCap) mr *= mCap / mLen;
    couple_torque = mr;
    mr_x = mr.x; mr_y = mr.y; mr_z = mr.z;
}}"""


GRANITE_MODEL = r"""
const float3 velB2A = (ALinVel + rotVelCPA) - (BLinVel + rotVelCPB);
const float vn = dot(velB2A, B2A);                 // > 0: separating
const float3 vt = velB2A - vn * B2A;
const float mEff = AOwnerMass * BOwnerMass / (AOwnerMass + BOwnerMass);
const float rMin = fminf(ARadius, BRadius);
float3 ut = make_float3(ut_x, ut_y, ut_z);
ut -= dot(ut, B2A) * B2A;                          // history into the current tangent plane
ut += ts * vt;
// The bending moment (paper s. 6.4, after Belheine et al. 2009): a spring k_r = R_i R_j k_t on the
// two spheres' relative rolling, capped at eta min(R_i, R_j) |F_n|, no failure of its own; a pure
// couple (A gets it, B its opposite). Only between rock spheres (eta_r > 0 for both).
const float etaR = fminf(eta_r[bodyAMatType], eta_r[bodyBMatType]);
float3 mr = make_float3(mr_x, mr_y, mr_z);
float3 wRoll = rotateToGlobal(AOriQ, ARotVel) - rotateToGlobal(BOriQ, BRotVel);
wRoll -= dot(wRoll, B2A) * B2A;
mr -= dot(mr, B2A) * B2A;                          // history into the current tangent plane
if (bond == 1.f) {                                 // marked at set-up: linked if within the range
    if (-overlapDepth <= gamma_int[bodyAMatType] * rMin) {
        bond = 2.f;
        overlap0 = (float)overlapDepth;
    } else {
        bond = 0.f;
        persistent = false;
    }
}
if (bond == 2.f) {
    const float kn = 2.f * E_micro[bodyAMatType] * ARadius * BRadius / (ARadius + BRadius);
    const float kt = nu[bodyAMatType] * kn;
    const float area = deme::PI * rMin * rMin;
    const float dy = -sigma_t[bodyAMatType] * area / kn;   // yield (tension: negative)
    const float db = 3.f * dy;                              // failure
    const float un = (float)overlapDepth - overlap0;        // > 0: compressed
    if (un >= db) {
        float fn = (un > dy) ? kn * un : kn * dy * (un - db) / (dy - db);
        fn -= 0.01f * sqrtf(kn * mEff) * vn;
        float3 ft = -kt * ut - 0.01f * sqrtf(kt * mEff) * vt;
        const float cap =
            mu[bodyAMatType][bodyBMatType] * fabsf(fn) + ((un > dy) ? cohesion[bodyAMatType] * area : 0.f);
        if (length(ft) <= cap) {
            force += fn * B2A + ft;
            ut_x = ut.x; ut_y = ut.y; ut_z = ut.z;
            BENDING_BOND
            return;
        }
    }
    bond = 0.f;                                     // broken in tension or shear, for good
    persistent = false;
    cracked[AOwner] = 1.f;
    cracked[BOwner] = 1.f;
}
// Hertz-Mindlin (paper s. 3.1) for pairs without a bond and for the plates, over the overlap beyond
// the pair's rest overlap when it was linked (a broken link's spheres were at rest there).
const float ov = (float)overlapDepth - fmaxf(overlap0, 0.f);
if (ov <= 0.f) {
    ut_x = ut_y = ut_z = 0.f;
    mr_x = mr_y = mr_z = 0.f;
    return;
}
const float R = ARadius * BRadius / (ARadius + BRadius);
const float sq = sqrtf(R * ov);
const float Sn = 2.f * E_eff[bodyAMatType][bodyBMatType] * sq;
const float St = 8.f * G_eff[bodyAMatType][bodyBMatType] * sq;
const float beta = beta_CoR[bodyAMatType][bodyBMatType];
const float fn = 4.f / 3.f * E_eff[bodyAMatType][bodyBMatType] * sq * ov
                 + 2.f * sqrtf(5.f / 6.f) * beta * sqrtf(Sn * mEff) * vn;  // beta < 0: opposes vn
float3 ft = -St * ut + 2.f * sqrtf(5.f / 6.f) * beta * sqrtf(St * mEff) * vt;
const float cap = mu[bodyAMatType][bodyBMatType] * fmaxf(fn, 0.f);
const float ftLen = length(ft);
if (ftLen > cap && ftLen > 0.f) {
    ft = ft * (cap / ftLen);
    ut = -ft / St;                                  // sliding: the spring holds the capped force
}
force += fmaxf(fn, 0.f) * B2A + ft;
ut_x = ut.x; ut_y = ut.y; ut_z = ut.z;
BENDING_HM
"""
GRANITE_MODEL = GRANITE_MODEL.replace("BENDING_BOND", _bending("kt", "fabsf(fn)")).replace(
    "BENDING_HM", _bending("St", "fmaxf(fn, 0.f)"))

# Granite and plates (paper s. 6.4, its table, after Potyondy & Cundall 2004 and Scholtes & Donze 2013).
RHO, E_ROCK, NU_ROCK, MU_ROCK = 2640.0, 60e9, 0.25, 0.30
UCS, SIGMA_T = 200e6, 9.3e6
# The bonds' cohesion (the paper's listing: 200 MPa); GRANITE_COHESION (Pa) sets another, for studies.
COHESION = float(os.environ.get("GRANITE_COHESION", "200e6"))
E_PLATE, NU_PLATE, MU_PLATE = 100e9, 0.30, 0.50
RADIUS = 1.2e-3
# The paper's specimen, 26,754 spheres, is this lattice's 21 x 26 x 49 (validation/README.md): HCPSampler
# puts floor((2h - offset) / pitch) + 1 centres along an axis (pitches 2R, sqrt(3) R and sqrt(8/3) R
# in x, y and z; rows offset by R in x, B layers by R in x and R / sqrt(3) in y), so these half sizes
# give 21, 26 and 49; 5.16 x 5.51 x 9.65 cm with the radii.
PAPER_BLOCK_HALF = [0.025, 0.0264, 0.0475]
# The bending moment's cap coefficient eta: 0 by default (no moment), as in the paper's own runs, whose
# listing's bending force is negligible (above); GRANITE_ETA=0.1 (its listing's value) applies the
# moment its text gives (validation/README.md: the specimen is then four times too strong).
ETA_R = float(os.environ.get("GRANITE_ETA", "0"))
# The bonds' shear stiffness over their normal one, k_t / k_n: the paper's nu (0.25);
# GRANITE_SHEAR_RATIO sets another, for studies (the affine moduli below follow it).
SHEAR_RATIO = float(os.environ.get("GRANITE_SHEAR_RATIO", str(NU_ROCK)))
_KT = "const float kt = nu[bodyAMatType] * kn;"
assert _KT in GRANITE_MODEL  # the bond branch's k_t, which the ratio replaces
GRANITE_MODEL = GRANITE_MODEL.replace(_KT, f"const float kt = {SHEAR_RATIO!r}f * kn;")


def _bond_stiffness(vectors, kn, kt):
    """Sum over bonds (centre-to-centre vectors, each bond once) of l^2 (k_n nnnn + k_t (d_ik n_j n_l -
    nnnn)): the elastic tensor times the volume of a uniformly strained set of springs k_n (central)
    and k_t (shear), symmetrised."""
    vectors = np.asarray(vectors, dtype=np.float64)
    lengths = np.linalg.norm(vectors, axis=1)
    n = vectors / lengths[:, None]
    w = lengths ** 2
    nnnn = np.einsum("b,bi,bj,bk,bl->ijkl", w, n, n, n, n)
    nn = np.einsum("b,bj,bl->jl", w, n, n)
    C = kn * nnnn + kt * (np.einsum("ik,jl->ijkl", np.eye(3), nn) - nnnn)
    C = 0.5 * (C + C.transpose(1, 0, 2, 3))
    return 0.5 * (C + C.transpose(0, 1, 3, 2))


def _uniaxial(C, axis):
    """Young's modulus along `axis` (uniaxial stress: 1 / S_aa of the compliance) and Poisson's ratio
    -S_ba / S_aa (b the next axis) of the elastic tensor C."""
    voigt = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]
    M = np.array([[C[i, j, k, m] * (1 if b < 3 else 2) for b, (k, m) in enumerate(voigt)] for (i, j) in voigt])
    S = np.linalg.inv(M)
    other = (axis + 1) % 3
    return 1.0 / S[axis, axis], -S[other, axis] / S[axis, axis]


def affine_modulus(links_per_shell, kn_over_e, radius=RADIUS, nu_micro=SHEAR_RATIO, axis=2):
    """Young's modulus along `axis` of an infinite HCP lattice of touching spheres stacked along z (axis
    2: its stacking axis c; axis 0: across the stacking, along a row of a layer), whose bonds are
    springs k_n (central) and k_t = nu k_n (shear) to the neighbours of the given shells (1: the 12
    nearest at a = 2R; 2: also the 6 at sqrt(2) a), deformed affinely, per unit E_micro (kn_over_e =
    k_n / E_micro). Also returns Poisson's ratio."""
    a = 2.0 * radius
    pts = []
    for k in range(-2, 3):
        for i in range(-3, 4):
            for j in range(-3, 4):
                off = (0.5 * a, a * math.sqrt(3) / 6) if k % 2 else (0.0, 0.0)
                pts.append((a * (i + 0.5 * j) + off[0], a * math.sqrt(3) / 2 * j + off[1], k * a * math.sqrt(2 / 3)))
    pts = np.array(pts)
    dist = np.linalg.norm(pts, axis=1)
    reach = {1: 1.01 * a, 2: 1.42 * a}[links_per_shell]
    vol = a ** 3 / math.sqrt(2)  # per sphere
    bonds = pts[(dist > 1e-12) & (dist <= reach)]  # a sphere's bonds, each shared by two spheres
    C = 0.5 * _bond_stiffness(bonds, kn_over_e, nu_micro * kn_over_e) / vol
    return _uniaxial(C, axis)


def specimen_modulus(pts, half, gamma_int, cut=False, radius=RADIUS, nu_micro=SHEAR_RATIO):
    """Young's modulus along z of the specimen itself (its sphere centres `pts`), deformed affinely, per
    unit E_micro: its bonds as the model makes them (surfaces within gamma_int R), the stress over
    its cross-section (section_area) and the strain over its outer layers' distance h, as the test
    measures them (so the volume is section x h). Its free faces lack the bonds of the infinite
    lattice's (affine_modulus): a small block is the softer."""
    pts = np.asarray(pts, dtype=np.float64)
    reach = (2.0 + gamma_int) * radius * (1 + 1e-9)
    order = np.argsort(pts[:, 2])
    p = pts[order]
    vectors = []
    for start in range(0, len(p), 256):  # rows in chunks: the pairs within reach of each
        rows = p[start:start + 256]
        hi = np.searchsorted(p[:, 2], rows[:, 2].max() + reach, side="right")
        cols = p[start:hi]
        d = rows[:, None, :] - cols[None, :, :]
        dist = np.linalg.norm(d, axis=2)
        idx_r, idx_c = np.nonzero((dist <= reach) & (dist > 0))
        keep = idx_c > idx_r  # each pair once (cols start at the chunk's first row)
        vectors.append(d[idx_r[keep], idx_c[keep]])
    low, high = outer_layers(pts)
    volume = section_area(pts, half, cut) * float(pts[high, 2].mean() - pts[low, 2].mean())
    C = _bond_stiffness(np.concatenate(vectors), radius, nu_micro * radius) / volume
    return _uniaxial(C, 2)[0]


def lattice(deme, half):
    """The HCP lattice of touching spheres filling the box of half sizes `half`, its stacking axis
    along z, or along x where GRANITE_C_AXIS=x (the sampler stacks its layers along z), so that the
    block is loaded across its layers' stacking rather than along it."""
    a = 2.0 * RADIUS
    if os.environ.get("GRANITE_C_AXIS", "z") == "x":
        pts = np.asarray(deme.HCPSampler(a).SampleBox([0, 0, 0], [half[2], half[1], half[0]]), dtype=np.float64)
        return pts[:, [2, 1, 0]]
    return np.asarray(deme.HCPSampler(a).SampleBox([0, 0, 0], half), dtype=np.float64)


def build(deme, half, gamma_int, e_micro, plate_speed, dt, jitter=0.0, seed=1, positions=None, sigma_t=SIGMA_T,
          plates=True, cohesion=COHESION):
    """The specimen (an HCP block of touching spheres filling the box of half sizes `half`, or the
    given sphere centres) between two plates, the bonds made, its spheres' micro tensile strength
    `sigma_t`. Families 3 and 4 are ready for grips (pull): held, and pulled up at `plate_speed`.
    Without `plates` there are none. Returns (solver, block batch, plate trackers or None,
    positions)."""
    sim = deme.DEMSolver()
    sim.SetVerbosity("ERROR")
    model = sim.DefineContactForceModel(GRANITE_MODEL)
    model.SetMustHaveMatProp(["E", "nu", "CoR", "E_micro", "sigma_t", "cohesion", "gamma_int", "eta_r"])
    model.SetMustPairwiseMatProp(["mu"])
    model.SetPerContactWildcards(["bond", "overlap0", "ut_x", "ut_y", "ut_z", "mr_x", "mr_y", "mr_z"])
    model.SetPerOwnerWildcards(["cracked"])
    rock = sim.LoadMaterial({"E": E_ROCK, "nu": NU_ROCK, "CoR": 0.5, "mu": MU_ROCK, "E_micro": e_micro,
                             "sigma_t": sigma_t, "cohesion": cohesion, "gamma_int": gamma_int,
                             "eta_r": ETA_R})
    plate = sim.LoadMaterial({"E": E_PLATE, "nu": NU_PLATE, "CoR": 0.5, "mu": MU_PLATE, "E_micro": 0.0,
                              "sigma_t": 0.0, "cohesion": 0.0, "gamma_int": 0.0, "eta_r": 0.0})
    sim.SetMaterialPropertyPair("mu", rock, plate, MU_PLATE)
    a = 2.0 * RADIUS
    pts = np.asarray(positions, dtype=np.float64) if positions is not None else lattice(deme, half)
    if jitter > 0.0:
        pts += np.random.default_rng(seed).uniform(-jitter * a, jitter * a, pts.shape)
    z_lo, z_hi = pts[:, 2].min(), pts[:, 2].max()
    span = 4.0 * max(half)
    sim.InstructBoxDomainDimension(span, span, span)
    mass = RHO * 4.0 / 3.0 * math.pi * RADIUS ** 3
    block = sim.AddClumps(sim.LoadSphereType(mass, RADIUS, rock), pts)
    if plates:
        bottom = sim.AddBCPlane([0, 0, z_lo - RADIUS], [0, 0, 1], plate)
        top = sim.AddBCPlane([0, 0, z_hi + RADIUS], [0, 0, -1], plate)
        bottom.SetFamily(1)
        top.SetFamily(2)
    sim.SetFamilyFixed(1)
    sim.SetFamilyPrescribedLinVel(2, "0", "0", f"{-plate_speed!r}")
    sim.SetFamilyFixed(3)
    sim.SetFamilyPrescribedLinVel(4, "0", "0", f"{plate_speed!r}")
    # Pairs within the interaction range must be in the contact set when the bonds are made.
    sim.SetFamilyExtraMargin(0, 0.5 * gamma_int * RADIUS + 0.02 * RADIUS)
    sim.SetGravitationalAcceleration([0, 0, 0])
    # Fragments that spall off a failing block fly at tens of m/s (a bond's elastic energy on one
    # sphere): they leave the domain and are removed, counted, rather than stopping the run.
    sim.SetDomainExitPolicy("remove")
    sim.SetInitTimeStep(dt)
    sim.Initialize()
    sim.MarkFamilyPersistentContact(0, 0)
    sim.SetFamilyContactWildcardValue(0, 0, "bond", 1.0)
    return sim, block, (sim.Track(bottom), sim.Track(top)) if plates else None, pts


def outer_layers(pts):
    """Masks of the outer layers of spheres, within R/2 of the lowest and of the highest centres (whole
    lattice layers when the stacking axis is z, the outer rows of every layer when it is x)."""
    return pts[:, 2] < pts[:, 2].min() + 0.5 * RADIUS, pts[:, 2] > pts[:, 2].max() - 0.5 * RADIUS


def section_area(pts, half, cut):
    """The specimen's cross-section: the lattice's extent plus a diameter each way, or, for a packing
    cut from a larger one (granite_packing.py), the box its centres were taken from (as much of its
    spheres' volume sticks out of that box as the cut-off spheres' reaches in)."""
    if cut:
        return 4.0 * half[0] * half[1]
    return (pts[:, 0].max() - pts[:, 0].min() + 2 * RADIUS) * (pts[:, 1].max() - pts[:, 1].min() + 2 * RADIUS)


# Instants of the plates' load per sample of the compression curve (compress).
LOAD_INSTANTS = 5
# The compression test ends when the stress has fallen below this fraction of its peak (the specimen
# has failed; the usual post-peak criterion of bonded-particle compression tests). GRANITE_STOP_RATIO
# sets another; 0 runs on to the end strain (the rubble's load after the collapse, for studies).
STOP_RATIO = float(os.environ.get("GRANITE_STOP_RATIO", "0.7"))


def compress(deme, half, gamma_int, e_micro, plate_speed, dt, end_strain, samples, jitter=0.0, positions=None,
             sigma_t=SIGMA_T, cohesion=COHESION, seed=1, stop_ratio=None):
    """Runs the test; returns a dict with the stress-strain curve (strain from the outer layers'
    mean heights, stress = mean plate load over the specimen's cross-section), the number of bonds
    and the final positions and crack flags. `jitter` (a fraction of the diameter) moves the lattice's
    spheres at random by up to that much each way (`seed` the generator's)."""
    stop_ratio = STOP_RATIO if stop_ratio is None else stop_ratio
    sim, block, (tr_bottom, tr_top), pts = build(deme, half, gamma_int, e_micro, plate_speed, dt, jitter, seed,
                                                 positions=positions, sigma_t=sigma_t, cohesion=cohesion)
    sim.DoDynamics(dt)  # the model links the pairs within range at its first call
    bonds0 = sim.GetNumPersistentContacts()
    tr = sim.Track(block)
    low, high = outer_layers(pts)
    area = section_area(pts, half, positions is not None)
    low_ids, high_ids = np.flatnonzero(low), np.flatnonzero(high)

    def mean_z(ids):
        z = []
        for i in ids:
            try:
                z.append(tr.Pos(int(i))[2])
            except deme.Error:  # removed (left the domain)
                pass
        return float(np.mean(z))

    def height():
        return mean_z(high_ids) - mean_z(low_ids)

    h0 = height()
    t_end = end_strain * (h0 + 2 * RADIUS) / plate_speed
    strain, stress, bonds = [0.0], [0.0], [bonds0]
    # Each sample: the plates' load at LOAD_INSTANTS evenly spaced instants, their median, and the
    # strain at the middle one: an instant's reading is not the specimen's stress where something
    # passing strikes a plate. (The GPa "spikes" once read after the collapse were fragments that
    # had left the domain, parked beyond it and still pressing on the infinite plates, an engine
    # fault since fixed: validation/README.md.)
    # The test ends once the specimen has failed: when the stress has fallen below `stop_ratio`
    # of the peak it reached (0: runs on to end_strain). Past that the plates compress the rubble
    # of a specimen that no longer exists, whose load is no strength of the rock.
    for _ in range(samples):
        loads = []
        for k in range(LOAD_INSTANTS):
            sim.DoDynamics(t_end / samples / LOAD_INSTANTS)
            loads.append(0.5 * (tr_top.ContactForce()[2] - tr_bottom.ContactForce()[2]))
            if k == LOAD_INSTANTS // 2:
                strain.append((h0 - height()) / h0)
        stress.append(float(np.median(loads)) / area)
        bonds.append(sim.GetNumPersistentContacts())
        peak = max(stress)
        if stop_ratio > 0 and peak > 0.05 * UCS and stress[-1] < stop_ratio * peak:
            break
    n = len(pts)
    kept, positions = [], []
    for i in range(n):
        try:
            positions.append(tr.Pos(i))
            kept.append(i)
        except deme.Error:
            pass
    # (owner by owner: the range call refuses a range that holds a removed owner)
    cracked = np.asarray([sim.GetOwnerWildcardValue("cracked", i, 1)[0] for i in kept], dtype=np.float64)
    return {"strain": np.array(strain), "stress": np.array(stress), "bonds": np.array(bonds), "spheres": n,
            "area": area, "height": h0, "positions": np.array(positions, dtype=np.float64), "cracked": cracked,
            "removed": sim.GetNumRemovedClumps()}


def pull(deme, half, gamma_int, e_micro, speed, dt, end_strain, samples, positions, sigma_t=SIGMA_T):
    """Direct tension of the specimen: once the bonds are made, its outer layers of spheres (within
    R/2 of the lowest and highest centres) become grips, the lower one held (family 3), the upper one
    pulled up at `speed` (family 4); no plates. Strain: the grips' separation over its start; stress:
    the bonds' pull on the upper grip over the section (positive in tension). Returns a dict with the
    curve and the peak."""
    sim, block, _, pts = build(deme, half, gamma_int, e_micro, speed, dt, positions=positions, sigma_t=sigma_t,
                               plates=False)
    sim.DoDynamics(dt)  # the model links the pairs within range at its first call
    tr = sim.Track(block)
    low, high = outer_layers(pts)
    families = np.where(low, 3, np.where(high, 4, 0)).astype(int)
    tr.SetFamilies(families.tolist())
    area = section_area(pts, half, positions is not None)
    h0 = float(pts[high, 2].mean() - pts[low, 2].mean())
    t_end = end_strain * h0 / speed
    strain, stress, bonds = [0.0], [0.0], [sim.GetNumPersistentContacts()]
    for k in range(1, samples + 1):
        sim.DoDynamics(t_end / samples)
        forces = tr.ContactForces()
        strain.append(speed * k * t_end / samples / h0)
        stress.append(-float(forces[high, 2].sum()) / area)
        bonds.append(sim.GetNumPersistentContacts())
    stress = np.array(stress)
    ipk = int(np.argmax(stress))
    return {"strain": np.array(strain), "stress": stress, "bonds": np.array(bonds), "peak": float(stress[ipk]),
            "peak_strain": float(strain[ipk]), "spheres": len(pts)}


def initial_modulus(strain, stress, lo=0.05 * UCS, hi=0.25 * UCS):
    """Least-squares slope of stress against strain over the samples of the loading branch (before
    the peak) whose stress lies in [lo, hi]: by default 10-50 MPa, the first quarter of the granite's
    strength, where the lattice's first bonds have not yet broken."""
    ipk = int(np.argmax(stress))
    s, e = stress[:ipk + 1], strain[:ipk + 1]
    sel = (s >= lo) & (s <= hi)
    if sel.sum() < 2:
        return float("nan")
    return float(np.polyfit(e[sel], s[sel], 1)[0])
