"""Stepping a scene until its grains are still: the loop the set-ups share (the crater's bed, the
silo, the repose heap)."""
import math

import numpy as np


def step_until_still(sim, tracker, t_min, t_max, v_mean, v_max=math.inf, frame=0.02):
    """Steps `frame` at a time until the tracked grains' mean speed is below v_mean and the fastest
    one's below v_max (m/s), after at least t_min and at most t_max seconds from the call. Returns the
    time it took, whether they came to rest and the fastest grain's speed then."""
    t0 = sim.GetSimTime()
    while True:
        sim.DoDynamics(frame)
        t = sim.GetSimTime() - t0
        v = np.linalg.norm(tracker.Velocities(), axis=1)
        still = bool(v.mean() < v_mean and v.max() < v_max)
        if (t >= t_min and still) or t >= t_max:
            return t, still, float(v.max())
