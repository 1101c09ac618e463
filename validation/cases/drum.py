"""Rotating drum: the angle of repose over friction and rolling resistance (paper s. 6.2.1), with
LIGGGHTS 3.8 on the same drums at three points.

Set-up (validation/drum_setup.py): a drum of inner diameter D = 0.19 m turning at 3.6 rpm about its
horizontal axis, half filled (the paper's number of grains per unit depth: 13,024 PS or 19,036 PC in
0.20 m). Mantle (an analytical cylinder) and both end walls (planes) turn with it; walls as in the
paper's own drum demos (DEM-Engine's DEMdemo_Granular_PlasticSphereDrum.cpp, 2023): E = 10 GPa,
nu = 0.3, grain-wall CoR = 0.5 and mu = 0.30 whatever the grains' mu, but grain-wall Crr = 0 (the
demo's 0.05 left out: a rolling resistance against a turning wall must see the wall's spin, which
LIGGGHTS's meshes do not carry into it). Grains, the paper's table: PS, spheres of r = 3 mm, rho = 1592 kg/m^3; PC,
"cylinders" of 5 spheres of r = 2 mm, centres 1 mm apart (8 mm long), with a solid cylinder's mass
and inertia at 1128 kg/m^3 (as the demo); E = 10 MPa, nu = 0.35, CoR = 0.85; Hertz-Mindlin
with the rolling resistance of Ai et al.'s model A, a couple against the owners' relative spin
(validation/rolling_model.py; DRUM_ROLLING=paper runs the default model, whose rolling term is the
paper's, for comparison: README). One simulation holds a drum per (mu, Crr) point, mu in
[0, 0.9] and Crr in [0, 0.08] (DRUM_GRID=<n_mu>x<n_Crr>, default 7x3; 13x5 is the paper's matrix).
The grains start on a jittered lattice whose surface is tilted 30 degrees the way the drum lifts it
(so that every point flows well within the paper's 2 s), settle 0.3 s with the drum at rest, then
the drum turns 2 s to steady state (the PS map 6 s: below) and 3 s more, over which the angle is
measured 30 times (every 0.1 s) and averaged, as in the paper. Time step 2e-5 s (10 % of the PS grains' Rayleigh time, 17 % of
a PC sphere's); contact detection at least every 20 steps on the CPU, 60 on the GPU.

Measurement (drum_setup.surface_angle): in the drum's cross-section (every grain's centre, whatever
its depth), bins two volume-equivalent diameters wide over the middle half of the drum (|x| <= R/2);
each bin's surface height is the mean height of its k highest grains (k = half a monolayer of the
bin); a least-squares line through the bins' heights; the angle is atan of its slope. A point's
uncertainty (se) is the samples' standard deviation over the square root of their effective number
(lag-1 autocorrelation).

What the full version changes from the paper, and why (on one H200 the 7 x 3 PS map took about 4
minutes and the PC map 7 before the custom models' apart pairs were made cheap, about 1.6 and 2.3 times
less since (validation/README.md), so they run as two commands, DRUM_RUNS=PS and DRUM_RUNS=PC; LIGGGHTS beside them on
the CPU): the PS map turns 6 s before it is measured, not 2 (DRUM_STEADY_PS): measured over 2.3-5.3 s
its drums' 3 s means still carried an uncertainty of up to 2.4 degrees (the surface swung between
avalanches), so that Crr's rise of 3 degrees at low mu could not be told from it; over 6.3-9.3 s the
same drums' uncertainty is 0.1-0.4 degrees (validation/README.md). It keeps the paper's depth, 0.20 m
(DRUM_DEPTH_PS); the PC
map's drums are 0.05 m deep (DRUM_DEPTH_PC; 4,759 clumps, 23,795 spheres a drum: at 0.20 m its
7 x 3 map alone would be 2 M spheres), end walls kept, so its angles include four times the end
walls' share of the paper's drum, and it runs the grid's first and last Crr only (Crr is not judged
for the cylinders; so that the map fits one 10-minute command; its drums turn the paper's 2 s;
DRUM_PC_CRR=c1,c2,... runs other Crr values of the grid, e.g. its middle ones as a second command). The LIGGGHTS points run on three more PS drums, 0.05 m deep
(DRUM_DEPTH_PEER: 3,256 spheres each, so that LIGGGHTS on the CPU keeps pace with the GPU), from the
engine's settled state (positions, velocities, spins) in both codes. DRUM_TIMES=settle,steady,measure; DRUM_TIMING=1
prints each run's phase timings and detection statistics.

Reference and verdicts: the paper's findings (s. 6.2.1; its figure's values are not in our data):
spheres at mu = 0 give under 5 degrees (every Crr); the angle rises with mu (every Crr, both
materials) and with Crr (every mu > 0, spheres; the paper finds Crr's effect on the cylinders small,
drawn, not judged): along each line no step falls by more than twice its se and the last point
exceeds the first by more than twice theirs. At (mu, Crr) = (0.3, 0), (0.6, 0.04), (0.9, 0.08) the
spheres' angle is within 2 degrees of LIGGGHTS 3.8's (drum_liggghts.in: Hertz-Mindlin with history,
CoR damping, constant directional torque rolling friction, the same law as the engine's model here; the drums as turning STL meshes of 96 flats lying at R), under mpirun
(DEME_LIGGGHTS_NP ranks; by default min(12, cores - 1) beside the GPU; on the CPU backend after the
engine, with min(12, cores) ranks, or one with OMP_NUM_THREADS=1). DRUM_RUNS=<names> runs some of PS-peer, PS and PC (e.g. PS-peer alone on
the CPU, engine and LIGGGHTS: 3 x 3,256 spheres, about 5 and 15 minutes on 2 cores).

On a GPU machine without LIGGGHTS the case runs the maps, writes the LIGGGHTS set-up beside its output
(<out>/drum_liggghts: the settled packings, the drums as STL, the input) and is listed as skipped;
DRUM_FROM=<that output folder> run.py drum, on a machine with LIGGGHTS, then runs LIGGGHTS there from
those packings and states every verdict, with the maps read back from <out>/drum-data.json. A map
too large for one command runs in parts: DRUM_SHARD=i/n runs the maps' mu columns i, i + n, ... only;
DRUM_FROM=<dir1>,<dir2>,... then judges and draws the parts together (e.g. the paper's 13 x 5 PS map:
DRUM_GRID=13x5 DRUM_RUNS=PS with DRUM_SHARD=1/2 and 2/2, 177 and 152 s on one H100).

--quick (CI, one core, about 200 s idle): spheres only; a thin drum (0.02 m deep, 1,302 spheres),
soft grains (E = 1 MPa, dt = 1e-4 s: 15 % of their Rayleigh time), four points, (mu, Crr) = (0, 0),
(0.15, 0), (0.5, 0), (0.15, 0.08), the last two of Crr's verdict as three replicas each (8 drums);
0.25 s of settling, 1.5 s to steady state, 30 samples over 1.5 s; LIGGGHTS (one process) at (0.15, 0)
only, on the same drum: in so thin a drum the flow at higher friction is intermittent and its 1-1.5 s
means scatter by up to 2 degrees between runs of either code. Why the replicas: with one drum per
point, six runs (packings of seeds 1-4, and 1-2 again with the CPU's force sums in another order)
gave Crr's rise at mu = 0.15 as 1.9-4.9 degrees against 2 se of 1.2-4.2, and one of the six failed
(one drum's mean at Crr = 0 came out at 30.2 +- 2.0 degrees where the others gave 27.5-28.9): a
single thin drum cannot tell Crr's rise from its own scatter every time. A replica starts from the
packing of the next seed (DRUM_SEED, default 1, sets the first); a point's angle is the mean of its
replicas' means, its se theirs combined (sqrt of the sum of squares, over their number).
"""
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from common import Case, commit, import_deme, read_parts, write_json  # noqa: E402
import drum_setup as ds  # noqa: E402

case = Case("drum", __doc__)
deme = import_deme()
import numpy as np  # noqa: E402

LIGGGHTS_POINTS = [(0.3, 0.0), (0.6, 0.04), (0.9, 0.08)]


def grid(spec):
    n_mu, n_crr = (int(v) for v in spec.lower().split("x"))
    return ([round(float(v), 4) for v in np.linspace(0, 0.9, n_mu)],
            [round(float(v), 4) for v in np.linspace(0, 0.08, n_crr)])


if case.quick:
    mus, crrs = [0.0, 0.15, 0.5], [0.0, 0.08]
    peer_points = [(0.15, 0.0)]
    # one run: the map's drums, one of them also the LIGGGHTS point
    settle, steady, measure = 0.25, 1.5, 1.5
    # Crr's two points as three replicas each (docstring: one thin drum's 1.5 s mean scatters by
    # about a degree from one packing to the next, as much as Crr's rise over its 2 se)
    runs = [dict(name="PS", grain=ds.PS, depth=0.02, young=1e6, dt=1e-4, map=True, peer=True, steady=steady,
                 points=[(0.0, 0.0), (0.15, 0.0), (0.5, 0.0), (0.15, 0.08)],
                 replicas={(0.15, 0.0): 3, (0.15, 0.08): 3})]
    processes, beside = 1, False
else:
    mus, crrs = grid(os.environ.get("DRUM_GRID", "7x3"))
    every = [(m, c) for c in crrs for m in mus]
    # the grid points nearest the three LIGGGHTS points
    peer_points = []
    for p in LIGGGHTS_POINTS:
        q = (min(mus, key=lambda m: abs(m - p[0])), min(crrs, key=lambda c: abs(c - p[1])))
        if q not in peer_points:
            peer_points.append(q)
    # DRUM_PC_CRR=c1,c2,...: the PC map's Crr values (the grid's first and last by default; e.g. its
    # middle ones as another command, joined with the first by DRUM_FROM)
    pc_crrs = sorted({crrs[0], crrs[-1]})
    if os.environ.get("DRUM_PC_CRR"):
        pc_crrs = sorted({round(float(v), 4) for v in os.environ["DRUM_PC_CRR"].split(",")})
        if any(c not in crrs for c in pc_crrs):
            raise ValueError(f"DRUM_PC_CRR={os.environ['DRUM_PC_CRR']!r}: Crr values of the grid {crrs} only")
    # first the drums LIGGGHTS runs too (thinner than the map's, so that LIGGGHTS keeps pace with the GPU),
    # then the two maps
    runs = [dict(name="PS-peer", grain=ds.PS, depth=float(os.environ.get("DRUM_DEPTH_PEER", "0.05")), young=ds.E,
                 dt=2e-5, map=False, peer=True, points=peer_points),
            dict(name="PS", grain=ds.PS, depth=float(os.environ.get("DRUM_DEPTH_PS", "0.20")), young=ds.E, dt=2e-5,
                 map=True, peer=False, points=every),
            dict(name="PC", grain=ds.PC, depth=float(os.environ.get("DRUM_DEPTH_PC", "0.05")), young=ds.E, dt=2e-5,
                 map=True, peer=False, points=[(m, c) for c in pc_crrs for m in mus])]
    chosen = os.environ.get("DRUM_RUNS")
    if chosen:
        names = chosen.split(",")
        unknown = [n for n in names if n not in [r["name"] for r in runs]]
        if unknown:
            raise ValueError(f"DRUM_RUNS: {unknown} not among PS-peer, PS, PC")
        runs = [r for r in runs if r["name"] in names]
    settle, steady, measure = (float(v) for v in os.environ.get("DRUM_TIMES", "0.3,2,3").split(","))
    # DRUM_SHARD=i/n: the maps' mu columns i, i + n, ... only (1-based), so that a map too large for
    # one command runs as n; DRUM_FROM=<dir1>,<dir2>,... draws and judges them together.
    shard = os.environ.get("DRUM_SHARD")
    if shard:
        i, n = (int(v) for v in shard.split("/"))
        if not 1 <= i <= n:
            raise ValueError(f"DRUM_SHARD={shard!r}: i/n with 1 <= i <= n")
        for run in runs:
            if run["map"]:
                run["points"] = [p for p in run["points"] if mus.index(p[0]) % n == i - 1]
    # The PS map turns 6 s before it is measured, not the paper's 2 (README: after 2 s its drums still
    # swung by up to 2.4 degrees between 3 s means; after 6 s by 0.2-0.4); DRUM_STEADY_PS sets it.
    for run in runs:
        run["steady"] = float(os.environ.get("DRUM_STEADY_PS", "6")) if run["name"] == "PS" else steady
    beside = case.backend != "cpu"  # LIGGGHTS on the CPU while the GPU runs the maps
    cores = os.cpu_count() or 1
    if os.environ.get("DEME_LIGGGHTS_NP"):
        processes = int(os.environ["DEME_LIGGGHTS_NP"])
    elif beside:
        processes = max(1, min(12, cores - 1))
    else:
        processes = 1 if os.environ.get("OMP_NUM_THREADS") == "1" else min(12, cores)
# The paper: 30 samples over the 3 s of measurement (DRUM_SAMPLES and DRUM_TIMES lengthen both, e.g.
# 90 over 9 s, for a longer average at the same 0.1 s spacing).
SAMPLES = int(os.environ.get("DRUM_SAMPLES", "30"))
# The packings' seed (the lattice's jitter; replicas take the next ones).
SEED = int(os.environ.get("DRUM_SEED", "1"))


def combined(stats):
    """One point from its replicas' (mean, se): the mean of their means, with the uncertainty that
    their own ones carry into it."""
    means, ses = np.array([m for m, _ in stats]), np.array([e for _, e in stats])
    return float(means.mean()), float(math.sqrt(np.sum(ses ** 2)) / len(stats))


def mean_se(a):
    """Mean of samples and its uncertainty: std / sqrt(n_eff), n_eff from the lag-1 autocorrelation."""
    a = np.asarray(a, float)
    n = len(a)
    s = a.std(ddof=1)
    rho = 0.0
    if s > 0:
        d = a - a.mean()
        rho = float(np.clip(np.sum(d[1:] * d[:-1]) / np.sum(d * d), 0.0, 0.95))
    n_eff = n * (1 - rho) / (1 + rho)
    return float(a.mean()), float(s / math.sqrt(n_eff))


# ---- the engine's maps; LIGGGHTS from the spheres' settled packings ----
results = {}
peer = {"points": peer_points, "folder": os.path.join(case.args.out, "drum_liggghts")}
handle = None
earlier = os.environ.get("DRUM_FROM")
origin = (case.backend, commit())
if earlier:
    # Finish an earlier run's peer verdicts here (a GPU machine without LIGGGHTS): its maps from
    # drum-data.json, LIGGGHTS from the settled packings it wrote, on this machine's CPU (where the
    # earlier run had no LIGGGHTS drums, its verdicts and plot alone).
    import shutil
    folders = earlier.split(",")
    parts = read_parts("DRUM_FROM", folders, "drum-data.json", ("settle_s", "steady_s", "measure_s", "samples",
                                                                  "rolling"), "not measured alike")
    data = parts[0]
    mus = sorted({m for p in parts for m in p["mu"]})
    crrs = sorted({c for p in parts for c in p["Crr"]})
    settle, steady, measure = data["settle_s"], data["steady_s"], data["measure_s"]
    SAMPLES = data.get("samples", SAMPLES)
    origin = (",".join(sorted({p.get("backend", "?") for p in parts})),
              ",".join(sorted({p.get("commit", "?") for p in parts})))  # where the maps ran
    peer_runs = [(p["peer_run"], folder) for p, folder in zip(parts, folders) if p["peer_run"]]
    peer_run, peer_folder = peer_runs[0] if peer_runs else (None, None)
    for part, folder in zip(parts, folders):
        for name, r in part["runs"].items():
            if name == peer_run and folder != peer_folder:
                continue
            run = dict(name=name, grain=ds.PC if name.startswith("PC") else ds.PS, depth=r["depth_m"],
                       young=r["E_Pa"], dt=r["dt_s"], map=name != "PS-peer", peer=name == peer_run,
                       steady=r.get("steady_s", steady), points=[(p["mu"], p["Crr"]) for p in r["points"]])
            res = dict(run=run, angles=[p["samples_deg"] for p in r["points"]],
                       stats=[(p["angle_deg"], p["se_deg"]) for p in r["points"]], wall=r["wall_s"],
                       steps=r["steps"], spheres=r["spheres"], grains=r["grains_per_drum"])
            if name not in results:
                results[name] = res
                continue
            # the same map from another shard: its points join the first part's (the walls and
            # spheres add up: the shards ran as separate simulations)
            have = results[name]
            for key in ("depth", "young", "dt", "steady"):
                if have["run"][key] != run[key]:
                    raise ValueError(f"DRUM_FROM: {name} differs in {key} between {folders}")
            have["run"]["points"] += run["points"]
            have["angles"] += res["angles"]
            have["stats"] += res["stats"]
            have["wall"] += res["wall"]
            have["spheres"] += res["spheres"]
    peer["points"] = peer_points = [tuple(p) for p in data["peer_points"]]
    if peer_run:  # else a run of the maps alone: verdicts and plot again, no LIGGGHTS
        peer.update(depth=results[peer_run]["run"]["depth"], dt=results[peer_run]["run"]["dt"], run=peer_run)
        shutil.copytree(os.path.join(peer_folder, "drum_liggghts"), peer["folder"], dirs_exist_ok=True)
    runs, beside = [], False
    processes = int(os.environ.get("DEME_LIGGGHTS_NP", "0")) or max(1, min(12, os.cpu_count() or 1))
    print(f"the maps of {earlier}; LIGGGHTS here on {processes} process(es)", flush=True)
rolling = data["rolling"] if earlier else os.environ.get("DRUM_ROLLING", "relative")
if rolling not in ("relative", "paper"):
    raise ValueError(f"DRUM_ROLLING={rolling!r}: 'relative' or 'paper'")
for run in runs:
    g = run["grain"]
    t0 = time.time()
    # a point's replicas start from packings of seeds DRUM_SEED, DRUM_SEED + 1, ...; the others
    # (and the first replica, the one LIGGGHTS gets) from DRUM_SEED's
    drum_points, drum_seeds = [], []
    for p in run["points"]:
        for r in range(run.get("replicas", {}).get(p, 1)):
            drum_points.append(p)
            drum_seeds.append(SEED + r)
    drums = ds.DrumSet(deme, g, run["depth"], drum_points, settle=settle, dt=run["dt"], young=run["young"],
                       max_cd_interval=20 if case.backend == "cpu" else 60, rolling=rolling, seeds=drum_seeds)
    print(f"{run['name']}: {len(drum_points)} drums of {drums.n} grains ({drums.sim.GetNumSpheres()} spheres), "
          f"depth {run['depth']} m, dt {run['dt']} s, set up in {time.time() - t0:.1f} s", flush=True)

    def settled(states, run=run, drum_points=drum_points):
        global handle
        if not run["peer"]:
            return
        idx = [drum_points.index(p) for p in peer_points]
        ds.write_peer_files(peer["folder"], run["grain"], run["depth"], peer_points, [states[i] for i in idx],
                            young=run["young"])
        peer.update(depth=run["depth"], dt=run["dt"], run=run["name"])
        if beside:
            handle = ds.start_liggghts(peer["folder"], peer_points, run["dt"], steady, measure, SAMPLES, processes)

    per_drum = drums.run(run["steady"], measure, SAMPLES, on_settled=settled)
    wall = time.time() - t0
    if os.environ.get("DRUM_TIMING") == "1":  # where the run's time went (phases, detection)
        drums.sim.ShowTimingStats()
        drums.sim.ShowThreadCollaborationStats()
    steps = int(round((settle + run["steady"] + measure) / run["dt"]))
    angles, stats, replicas = [], [], []
    for p in run["points"]:
        ks = [k for k, q in enumerate(drum_points) if q == p]
        st = [mean_se(per_drum[k]) for k in ks]
        angles.append(per_drum[ks[0]])  # the samples drawn: the first replica's
        stats.append(combined(st))
        replicas.append([{"seed": drum_seeds[k], "angle_deg": round(m, 3), "se_deg": round(e, 3)}
                         for k, (m, e) in zip(ks, st)])
    results[run["name"]] = dict(run=run, angles=angles, stats=stats, wall=wall, steps=steps,
                                spheres=drums.sim.GetNumSpheres(), grains=drums.n, replicas=replicas)
    print(f"{run['name']}: {wall:.0f} s ({steps} steps, {drums.sim.GetNumSpheres() * steps / wall:.3g} sphere-steps/s)",
          flush=True)
    for p, (m, se), reps in zip(run["points"], stats, replicas):
        each = (" (replicas " + ", ".join(f"{r['angle_deg']:.2f} +- {r['se_deg']:.2f}" for r in reps) + ")"
                if len(reps) > 1 else "")
        print(f"  mu {p[0]:.3f} Crr {p[1]:.3f}: {m:6.2f} +- {se:.2f} deg{each}")
    del drums

if not beside and peer.get("run"):
    handle = ds.start_liggghts(peer["folder"], peer_points, peer["dt"], steady, measure, SAMPLES, processes)
peer_result, peer_error = None, None
if handle:
    try:
        peer_result = ds.finish_liggghts(handle, ds.PS, peer["depth"])
    except RuntimeError as e:
        peer_error = str(e)
        print(peer_error)

# ---- verdicts ----
skipped = None
ps = results.get("PS")  # None where DRUM_RUNS left the map out
ps_peer = results.get(peer.get("run"))
maps = {name: res for name, res in results.items() if res["run"]["map"]}


def lookup(res, mu, crr):
    i = res["run"]["points"].index((mu, crr))
    return res["stats"][i], res["angles"][i]


def rises(res, line):
    """Along a line of (mu, Crr) points: (passed, words). No step falls by more than twice its
    uncertainty; the last exceeds the first by more than twice theirs."""
    st = [lookup(res, *p)[0] for p in line]
    m = np.array([s[0] for s in st])
    se = np.array([s[1] for s in st])
    steps = np.diff(m)
    tol = 2 * np.sqrt(se[1:] ** 2 + se[:-1] ** 2)
    worst = int(np.argmin(steps - (-tol)))
    rise, rise_tol = m[-1] - m[0], 2 * math.hypot(se[0], se[-1])
    ok = bool(np.all(steps >= -tol) and rise > rise_tol)
    return ok, (f"{m[0]:.1f} -> {m[-1]:.1f} ({rise:+.1f}, 2 se {rise_tol:.1f}); "
                f"worst step {steps[worst]:+.1f} (2 se {tol[worst]:.1f})")


zero = [lookup(ps, 0.0, c)[0][0] for c in crrs if (0.0, c) in ps["run"]["points"]] if ps is not None else []
if zero:  # (a shard of the map without mu = 0 has no such verdict)
    case.check("spheres at mu = 0: largest angle over Crr (deg)", "< 5", "paper s. 6.2.1 (near-horizontal surface)",
               round(max(abs(v) for v in zero), 2), "5 deg", max(abs(v) for v in zero) < 5)

for name, res in maps.items():
    words, ok_all = [], True
    for c in crrs:
        line = [(m, c) for m in mus if (m, c) in res["run"]["points"]]
        if len(line) < 2:
            continue
        ok, w = rises(res, line)
        ok_all &= ok
        words.append(f"Crr {c:g}: {w}")
    if words:  # (a shard with one mu has no line along mu)
            case.check(f"{name}: angle rises with mu (every Crr)", "rising", "paper s. 6.2.1", "; ".join(words),
                   "no step down beyond 2 se; end - start beyond 2 se", ok_all)
if ps is not None:
    words, ok_all = [], True
    for m in mus:
        line = [(m, c) for c in crrs if (m, c) in ps["run"]["points"]]
        if m == 0.0 or len(line) < 2:
            continue
        ok, w = rises(ps, line)
        ok_all &= ok
        words.append(f"mu {m:g}: {w}")
    if words:
        case.check("PS: angle rises with Crr (every mu > 0)", "rising", "paper s. 6.2.1", "; ".join(words),
                   "no step down beyond 2 se; end - start beyond 2 se", ok_all)

if ps_peer is None:
    print("the LIGGGHTS drums (PS-peer) were not among DRUM_RUNS: no peer verdict")
elif peer_error:
    case.check("LIGGGHTS 3.8 run (its log: <out>/drum_liggghts/liggghts.out)", "finished",
               "validation/drum_liggghts.in", peer_error.splitlines()[0], "needed", False)
elif peer_result is None and case.backend == "cpu":
    case.check("LIGGGHTS 3.8 installed (apt-get install liggghts; scripts/setup.sh does)", "found",
               "validation/drum_liggghts.in", "missing", "needed", False)
elif peer_result is None:
    # as Case.require_liggghts: a GPU machine may have no LIGGGHTS; the maps ran, the case is skipped
    skipped = ("LIGGGHTS is not installed on this machine: the maps ran (their verdicts in drum.json, the "
               "angles in drum-data.json, the plot in drum.png), the LIGGGHTS points did not")
else:
    l_angles, l_wall, l_np = peer_result
    print(f"LIGGGHTS: {l_wall:.0f} s on {l_np} process(es)")
    for k, p in enumerate(peer_points):
        (m_e, se_e), _ = lookup(ps_peer, *p)
        m_l, se_l = mean_se(l_angles[k])
        print(f"  mu {p[0]:.3f} Crr {p[1]:.3f}: engine {m_e:.2f} +- {se_e:.2f}, LIGGGHTS {m_l:.2f} +- {se_l:.2f}")
        case.check(f"PS angle at mu = {p[0]:g}, Crr = {p[1]:g}, {peer['depth']:g} m deep drum (deg)", round(m_l, 2),
                   "LIGGGHTS 3.8, same drum, packing, model and time step", round(m_e, 2), "2 deg",
                   abs(m_e - m_l) <= 2.0)

# ---- data and plot ----
data = {"settle_s": settle, "steady_s": steady, "measure_s": measure, "samples": SAMPLES, "mu": mus, "Crr": crrs,
        "walls": ds.WALL_PAIR, "rolling": rolling, "peer_run": peer.get("run"), "peer_points": peer_points,
        "backend": origin[0], "commit": origin[1], "runs": {}}
for name, res in results.items():
    r = res["run"]
    data["runs"][name] = {
        "depth_m": r["depth"], "E_Pa": r["young"], "dt_s": r["dt"], "steady_s": r["steady"],
        "grains_per_drum": res["grains"],
        "spheres": res["spheres"], "steps": res["steps"], "wall_s": round(res["wall"], 1),
        "points": [dict({"mu": p[0], "Crr": p[1], "angle_deg": round(s[0], 3), "se_deg": round(s[1], 3),
                         "samples_deg": [round(float(v), 3) for v in a]},
                        **({"replicas": reps} if len(reps) > 1 else {}))
                   for p, s, a, reps in zip(r["points"], res["stats"], res["angles"],
                                            res.get("replicas", [[]] * len(r["points"])))]}
if peer_result is not None:
    data["liggghts"] = {"wall_s": round(l_wall, 1), "processes": l_np, "depth_m": peer["depth"], "points": [
        {"mu": p[0], "Crr": p[1], "angle_deg": round(mean_se(a)[0], 3), "se_deg": round(mean_se(a)[1], 3),
         "samples_deg": [round(float(v), 3) for v in a]} for p, a in zip(peer_points, l_angles)]}
write_json(os.path.join(case.args.out, "drum-data.json"), data)

panels = len(maps) + (ps_peer is not None)  # the maps, and the LIGGGHTS drums' samples if they ran
fig, axes = case.figure(1, panels, figsize=(4.8 * panels, 4.2))
axes = np.atleast_1d(axes)  # one panel: a single Axes
from matplotlib.patches import Rectangle  # noqa: E402 (after case.figure chose the backend)
for ax, (name, res) in zip(axes, maps.items()):
    # cells in grid index space, labelled with the values
    img = np.full((len(crrs), len(mus)), np.nan)
    for p, s in zip(res["run"]["points"], res["stats"]):
        img[crrs.index(p[1]), mus.index(p[0])] = s[0]
    im = ax.imshow(img, origin="lower", aspect="auto", cmap="viridis", vmin=0, vmax=max(45.0, float(np.nanmax(img))))
    small = len(mus) > 7
    for p, s in zip(res["run"]["points"], res["stats"]):
        ax.text(mus.index(p[0]), crrs.index(p[1]), f"{s[0]:.1f}", ha="center", va="center", fontsize=5 if small else 7,
                color="w" if s[0] < 25 else "k")
    if res["run"]["peer"] and peer_result is not None:
        for k, p in enumerate(peer_points):
            i, j = mus.index(p[0]), crrs.index(p[1])
            ax.add_patch(Rectangle((i - 0.45, j - 0.45), 0.9, 0.9, fill=False, ec="r", lw=1.5))
            ax.text(i, j - 0.3, f"L {mean_se(l_angles[k])[0]:.1f}", ha="center", va="center",
                    fontsize=5 if small else 7, color="r", bbox=dict(fc="w", ec="none", pad=0.3, alpha=0.8))
    fig.colorbar(im, ax=ax, label="angle of repose (deg)")
    r = res["run"]
    ax.set_xticks(range(len(mus)), [f"{m:g}" for m in mus], fontsize=6)
    ax.set_yticks(range(len(crrs)), [f"{c:g}" for c in crrs], fontsize=6)
    ax.set_xlabel("mu (grain-grain; grain-wall 0.30)", fontsize=8)
    ax.set_ylabel("Crr (grain-grain; grain-wall 0)", fontsize=8)
    ax.set_title(f"{name}: D 0.19 m, depth {r['depth']:g} m, E {r['young'] / 1e6:g} MPa"
                 + ("; red: LIGGGHTS" if res["run"]["peer"] else ""), fontsize=8)
if ps_peer is not None:
    ax = axes[-1]
    t = settle + steady + (np.arange(SAMPLES) + 1) * measure / SAMPLES
    for k, p in enumerate(peer_points):
        ax.plot(t, lookup(ps_peer, *p)[1], "-", color=f"C{k}", label=f"engine mu {p[0]:g}, Crr {p[1]:g}")
        if peer_result is not None:
            ax.plot(t, l_angles[k], "--", color=f"C{k}", label="LIGGGHTS 3.8")
    ax.set(xlabel="time (s)", ylabel="angle (deg)",
           title=f"PS, {peer['depth']:g} m deep: the {SAMPLES} samples, engine (solid) and LIGGGHTS (dashed)")
    ax.title.set_fontsize(8)
    ax.legend(fontsize=6)
case.save(fig, origin=None if not earlier else f"maps on {origin[0]}, {origin[1]}")
case.finish(skipped=skipped)
