"""The heaviest top sphere a three-sphere stack holds (the paper's s. 3.3.2 test), from statics.

Two spheres of mass m1 and radius R lie on a floor with a gap d between them; a third of radius R
and mass m2 rests on both. By symmetry the top sphere does not turn and each bottom sphere carries
half its weight, W = m2 g / 2. Let theta be the angle of a top contact's normal from the vertical,
sin(theta) = (R + d/2) / (2R), c = cos(theta), t = tan(theta/2). On the left bottom sphere act: the
top contact's normal force N and friction T (on the top sphere T points up along the tangent), the
floor's normal force N_f and friction F, and the rolling-resistance moments of both contacts, whose
sum is R s, s > 0 when it opposes the bottom sphere's rolling outward (the collapse in which the
bottom spheres roll apart on the floor and the top contacts slide), s < 0 the other way.

    top sphere, vertical:      N c + T sin(theta) = W
    bottom sphere, horizontal: F = N sin(theta) - T c
    bottom sphere, moments:    R F - R T - R s = 0  (friction at the floor and at the top contact)

give N = W + s t, T = N t - s / (1 + c), F = N t + s c / (1 + c), N_f = m1 g + W. The stack stands if
some s satisfies every contact's limit (a static friction force and a rolling moment may take any
value up to their caps; the model's rolling moment is Crr R times the contact's normal force):

    |T| <= mu N   (the top contacts stick)
    |F| <= mu N_f (the floor contacts stick)
    |s| <= Crr (N_f + N)  (the two rolling moments together).

With Crr = 0 the stack stands for every m2 if t <= mu and for none otherwise (friction alone gives
no critical mass); with rolling resistance a stack with t > mu stands up to a critical m2, which
`critical_mass` finds by bisection on W. The paper's test (after Luning et al.'s friction-model study
that it cites) finds that critical mass by raising m2 in small steps.
"""
import math


def stands(W, d, mu, crr, R, m1, g):
    """True when a top load W (N per bottom sphere) leaves a feasible moment s."""
    theta = math.asin((R + 0.5 * d) / (2.0 * R))
    c, t = math.cos(theta), math.tan(0.5 * theta)
    nf = m1 * g + W
    # With N = W + s t, each limit is a bound on s.
    # T <= mu N:  s (t^2 - mu t - 1/(1+c)) <= W (mu - t), the factor negative while theta < 60 deg
    # (t^2 < 1/3 < 1/(1+c)), i.e. gaps d < (sqrt(3) - 1) 2R
    if theta >= math.radians(60.0):
        raise ValueError(f"gap {d} m: the analysis needs theta < 60 deg")
    a = t * t - mu * t - 1.0 / (1.0 + c)
    bounds_lo, bounds_hi = [W * (mu - t) / a], []
    # T >= -mu N:  s (1/(1+c) - t^2 - mu t) <= W (t + mu)
    b = 1.0 / (1.0 + c) - t * t - mu * t
    if b > 0:
        bounds_hi.append(W * (t + mu) / b)
    # -mu N_f <= F = W t + s (t^2 + c/(1+c)) <= mu N_f
    k = t * t + c / (1.0 + c)
    bounds_hi.append((mu * nf - W * t) / k)
    bounds_lo.append((-mu * nf - W * t) / k)
    # |s| <= crr (nf + W + s t): for s >= 0, s (1 - crr t) <= crr (nf + W); for s < 0, -s (1 + crr t) <= crr (nf + W)
    cap_pos = crr * (nf + W) / (1.0 - crr * t)
    cap_neg = -crr * (nf + W) / (1.0 + crr * t)
    return max(bounds_lo + [cap_neg]) <= min(bounds_hi + [cap_pos])


def critical_mass(d, mu, crr, R, m1, g=9.81):
    """The heaviest m2 the stack holds (kg); math.inf when it holds every mass, 0 when none."""
    if not stands(1e-9, d, mu, crr, R, m1, g):
        return 0.0
    hi = 1e6
    if stands(hi, d, mu, crr, R, m1, g):
        return math.inf
    lo = 1e-9
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stands(mid, d, mu, crr, R, m1, g) else (lo, mid)
    return 2.0 * lo / g
