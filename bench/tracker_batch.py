#!/usr/bin/python3
"""TRACKER-BATCH: a tracker's batch calls on a batch of a million clumps, from Python (one JSON line
per call): Positions(), Velocities(), AngularVelocities(), OriQs(), ContactForces(), SetPositions(),
and for scale the per-owner Pos(i) over the first 10^4 owners.

  PYTHONPATH=build/python /usr/bin/python3 bench/tracker_batch.py [clumps] [repeats]

The clumps are one-sphere clumps on a grid, apart (no contacts), in zero gravity; one step is run
so that the state is a running simulation's. Wall times are the median and minimum over repeats.
"""
import json
import os
import platform
import statistics
import sys
import time

import numpy as np

import deme


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def timed(fn, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), min(times)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 20
    side = int(round(n ** (1 / 3))) + 1
    sim = deme.DEMSolver()
    sim.SetVerbosity("ERROR")
    mat = sim.LoadMaterial({"E": 1e8, "nu": 0.3, "CoR": 0.5, "mu": 0.5})
    spacing = 0.01
    sim.InstructBoxDomainDimension(side * spacing + 0.1, side * spacing + 0.1, side * spacing + 0.1)
    tmpl = sim.LoadSphereType(1e-3, 0.004, mat)
    pts = deme.GridSampler(spacing).SampleBox([0, 0, 0], [side * spacing / 2] * 3)[:n]
    assert len(pts) == n, len(pts)
    batch = sim.AddClumps(tmpl, pts)
    sim.SetInitTimeStep(1e-5)
    sim.SetGravitationalAcceleration([0, 0, 0])
    t0 = time.perf_counter()
    sim.Initialize()
    init_s = time.perf_counter() - t0
    sim.DoDynamics(1e-5)
    tr = sim.Track(batch)
    pos = tr.Positions()
    common = {"bench": "tracker_batch", "backend": sim.GetBackend(), "device": cpu_name(),
              "cpu_threads": os.cpu_count(), "clumps": n, "repeats": repeats}
    cases = [("Positions", tr.Positions), ("Velocities", tr.Velocities),
             ("AngularVelocities", tr.AngularVelocities), ("OriQs", tr.OriQs),
             ("ContactForces", tr.ContactForces), ("ContactTorques", tr.ContactTorques),
             ("SetPositions", lambda: tr.SetPositions(pos))]
    for name, fn in cases:
        med, best = timed(fn, repeats)
        print(json.dumps(dict(common, case=name, wall_ms_median=round(1e3 * med, 3), wall_ms_min=round(1e3 * best, 3))))
    k = min(n, 10_000)
    med, best = timed(lambda: [tr.Pos(i) for i in range(k)], max(1, repeats // 4))
    print(json.dumps(dict(common, case="Pos(i) loop, first %d owners" % k, wall_ms_median=round(1e3 * med, 3),
                          wall_ms_min=round(1e3 * best, 3), per_owner_us=round(1e6 * med / k, 3))))
    print(json.dumps(dict(common, case="Initialize", wall_ms_median=round(1e3 * init_s, 1))))
    np.testing.assert_allclose(tr.Positions(), pts, atol=1e-5)  # and the answer is right


if __name__ == "__main__":
    main()
