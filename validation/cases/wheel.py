"""A grousered wheel crossing a bed, with the whole bed active and with an active box (paper s. 6.5.2).

Set-up (validation/wheel_setup.py): a soil bin as wide as the wheel (42 mm; frictionless side walls,
as a glass-walled bin, so the flow is plane) of spheres of r = 2.25, 2.5 and 2.75 mm (E = 10 MPa,
nu = 0.3, CoR = 0.3, mu = 0.5, Crr = 0.05, 2500 kg/m^3; dt = 20 us), filled on a hexagonal lattice
and settled once (0.15 s; the checkpoint is read back by every run). The wheel: a mesh built in
code, rim radius R = 40 mm, 40 mm wide, 12 grousers 5 mm high, 0.15 kg (a load of 1.47 N, which
sinks it 9-14 mm). Its forward speed is prescribed, v = 0.2 m/s, and its spin
w = v / (R (1 - slip)), slip on the rim radius; its vertical motion is free under its weight. It
starts at rest vertically, its lowest grouser's tip on the bed's surface (the mean, over 1 cm cells
along its path, of the highest grain top), and drives `travel` metres. Full version: bin 0.8 m long
and 35 mm deep (9,152 grains), 0.5 m of travel (2.5 s, 125,000 steps), slips 0.15, 0.25, 0.35 and
0.5; each slip is run three times: whole bed active, with the active box, and a control of the whole
bed with one grain at the bin's far end (0.7 m ahead of the wheel) lifted by 1 um at the start.
--quick reduces the bin to 0.3 m and 30 mm (2,968 grains), the travel to 0.1 m (0.5 s), the slips to
0.25 and 0.5, leaves out the control and judges the sinkage only (below).

The active box: grains whose centre lies within 90 mm behind or ahead of the axle are active (family
0), grains more than 100 mm behind or ahead fall dormant where they are (fixed, no contacts among
themselves or with the wheel: docs/active-box.md); the conditions are of X and t (the axle's x is
prescribed) and are checked at every contact detection (on the CPU at a fixed schedule, at most
30 steps apart and synchronous, so that the box runs are reproducible: wheel_setup.py). Its size:
twice the wheel's outer radius (45 mm) each way, so that the bow wave ahead of the wheel and the
rut's relaxation behind it lie inside. Checked in the whole-bed run by how far the grains that lay
outside it moved (printed, and in out/wheel-data.json), and in the box run by the gap between the
wheel's reach and the nearest dormant grain, which must stay positive (the wheel must never reach a
grain the box holds dormant).

Measured: drawbar pull = the contact force of the grains on the wheel along the travel (+x), i.e.
the net traction (positive: the wheel could pull a load; negative: net resistance); sinkage = the
drop of the axle below its starting height (grouser tip on the surface). Both are sampled every 25
steps (0.5 ms) and averaged over the largest whole number of grouser periods from 0.3 s (0.1 s with
--quick) to the run's end, past the wheel's landing (about 0.08 s); their standard errors are from
the spread of the per-period means.

Reference: the whole-bed run itself. Two runs that differ in anything (even by the control's 1 um)
decorrelate within about 0.1 s (DEM is chaotic), so each comparison is of two realisations of the
same drive, and their difference includes the runs' own scatter, which the control measures.
Verdicts: the box run's sinkage within 5 % of the whole bed's at every slip (the control's sinkage
differs by at most 3 %); its drawbar pull within 5 % of the whole bed's at the largest slip, 0.5,
only: there the drawbar pull is largest (a quarter of the load) and the control differs by 2-8 %,
while at slip 0.15 (0.12-0.18 N) the control differs by 4-18 %, so a 5 % verdict there judges the
scatter, not the box (all slips' differences are printed and plotted). With --quick the drawbar
pull's means (over 5-7 grouser periods, while it is still settling) carry standard errors of
10-20 %, several times the tolerance: plotted, not judged. Also judged, in both: the wheel never
reached a dormant grain. Reported: each run's stepping wall time and the ratio whole bed / box.
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from common import Case, import_deme, write_json  # noqa: E402
import wheel_setup as ws  # noqa: E402

case = Case("wheel", __doc__)
deme = import_deme()
import numpy as np  # noqa: E402

if case.quick:
    BIN = ws.Bin(length=0.3, depth=0.03, x0=0.08, travel=0.1)
    SLIPS, T_FROM, CONTROL = [0.25, 0.5], 0.1, False
else:
    BIN = ws.Bin(length=0.8, depth=0.035, x0=0.1, travel=0.5)
    SLIPS, T_FROM, CONTROL = [0.15, 0.25, 0.35, 0.5], 0.3, True
DP_SLIP = SLIPS[-1]  # the slip at which the drawbar pull is judged (header)
BOX = (0.09, 0.09, 0.01)  # back, front, hysteresis (m)
T_SETTLE, SAMPLE = 0.15, 25
ws.CD_FREQ = None if case.backend == "cuda" else 30  # reproducible box runs on the CPU (wheel_setup.py)
T_RUN = BIN.travel / ws.V_WHEEL
SRC = "the whole-bed run of the same drive (paper s. 6.5.2: the box reproduces the full domain)"

with tempfile.TemporaryDirectory() as tmp:
    ckpt = os.path.join(tmp, "bed.ckpt")
    bed = ws.settle(deme, BIN, ckpt, T_SETTLE)
    print(f"bed: {bed['grains']} grains settled in {bed['wall']:.1f} s (kinetic energy {bed['ke']:.1e} m g r per "
          f"grain), surface at {bed['surface'] * 1e3:.1f} mm", flush=True)
    runs = {}
    for slip in SLIPS:
        runs[slip] = {"full": ws.drive(deme, BIN, ckpt, bed["surface"], slip, T_RUN, SAMPLE, snapshots=25)}
        runs[slip]["box"] = ws.drive(deme, BIN, ckpt, bed["surface"], slip, T_RUN, SAMPLE, box=BOX)
        if CONTROL:
            runs[slip]["control"] = ws.drive(deme, BIN, ckpt, bed["surface"], slip, T_RUN, SAMPLE, nudge=1e-6)
        for kind, r in runs[slip].items():
            r["means"] = ws.window_means(r, slip, T_FROM)
            dp, dp_se, s, s_se, k, t0 = r["means"]
            print(f"slip {slip:.2f} {kind:7s}: drawbar pull {dp:+.4f} +- {dp_se:.4f} N, sinkage {s * 1e3:.3f} +- "
                  f"{s_se * 1e3:.3f} mm ({k} grouser periods from {t0:.3f} s), stepping {r['wall']:.1f} s", flush=True)

# Verdicts.
record = {"grains": bed["grains"], "settle_wall_s": round(bed["wall"], 2), "slips": {}}
for slip in SLIPS:
    full, box = runs[slip]["full"], runs[slip]["box"]
    dp_f, dpse_f, s_f, sse_f, _, _ = full["means"]
    dp_b, dpse_b, s_b, sse_b, _, _ = box["means"]
    case.check(f"slip {slip}: sinkage with the active box (mm)", round(s_f * 1e3, 3), SRC, round(s_b * 1e3, 3), "5 %",
               abs(s_b - s_f) <= 0.05 * abs(s_f))
    if slip == DP_SLIP and not case.quick:
        case.check(f"slip {slip}: drawbar pull with the active box (N)", round(dp_f, 4), SRC, round(dp_b, 4), "5 %",
                   abs(dp_b - dp_f) <= 0.05 * abs(dp_f))
    moved = ws.outside_motion(BIN, full["snaps"], BOX[0], BOX[1]) / ws.R_GRAIN
    woke = int(np.count_nonzero(box["ever_active"] & (full["snaps"][0][1][:, 0] > BIN.x0 + BOX[1])))
    entry = {"wall_full_s": round(full["wall"], 2), "wall_box_s": round(box["wall"], 2),
             "wall_ratio": round(full["wall"] / box["wall"], 2),
             "active_box": [a for _, a in box["active"]], "closest_dormant_gap_mm": round(min(box["gap"]) * 1e3, 2),
             "woken_ahead": woke, "outside_motion_p99_r": round(float(np.percentile(moved, 99)), 3),
             "outside_motion_max_r": round(float(moved.max()), 3)}
    for kind, r in runs[slip].items():
        dp, dp_se, s, s_se, k, t0 = r["means"]
        entry[kind] = {"drawbar_pull_N": round(dp, 4), "drawbar_pull_se_N": round(dp_se, 4),
                       "sinkage_mm": round(s * 1e3, 3), "sinkage_se_mm": round(s_se * 1e3, 3),
                       "periods": k, "window_s": [round(t0, 3), round(T_RUN, 3)], "wall_s": round(r["wall"], 2)}
    record["slips"][str(slip)] = entry
    diffs = ", ".join(f"{k} {100 * (r['means'][0] / dp_f - 1):+.1f} % and {100 * (r['means'][2] / s_f - 1):+.2f} %"
                      for k, r in runs[slip].items() if k != "full")
    print(f"slip {slip:.2f}: drawbar pull and sinkage against the whole bed's: {diffs}")
    print(f"slip {slip:.2f}: stepping {full['wall']:.1f} s whole bed, {box['wall']:.1f} s box "
          f"({full['wall'] / box['wall']:.2f}x); active grains in the box {min(entry['active_box'])}-"
          f"{max(entry['active_box'])} of {bed['grains']}; {woke} grains ahead of the box woke up; grains outside "
          f"the box in the whole-bed run moved at most {moved.max():.2f} r (99th percentile "
          f"{np.percentile(moved, 99):.3f} r)")
gap = min(min(runs[s]["box"]["gap"]) for s in SLIPS)
case.check("closest approach of the wheel's reach to a dormant grain (mm)", "> 0", "the active box's purpose "
           "(docs/active-box.md: the wheel's contacts with dormant grains are off)", round(gap * 1e3, 2), "positive",
           gap > 0)
write_json(os.path.join(case.args.out, "wheel-data.json"), record)

# The plot: drawbar pull and sinkage against slip, one drive's time series, the wall times.
fig, axes = case.figure(2, 2, figsize=(11, 8))
styles = {"full": ("o-", "C0", "whole bed"), "box": ("s--", "C3", "active box"),
          "control": ("^:", "gray", "whole bed, one grain lifted 1 um (scatter)")}
for ax, idx, scale, label in ((axes[0][0], 0, 1.0, "drawbar pull (N)"), (axes[0][1], 2, 1e3, "sinkage (mm)")):
    for kind, (fmt, c, name) in styles.items():
        if kind not in runs[SLIPS[0]]:
            continue
        y = [runs[s][kind]["means"][idx] * scale for s in SLIPS]
        e = [runs[s][kind]["means"][idx + 1] * scale for s in SLIPS]
        ax.errorbar(SLIPS, y, yerr=np.nan_to_num(e), fmt=fmt, color=c, capsize=3, label=name)
    ax.set(xlabel="slip", ylabel=label, title=f"{label.split(' (')[0]} against slip (means over whole grouser periods)")
    ax.legend(fontsize=7)
axes[0][0].axhline(0, color="k", lw=0.5)
judged = "quick: not judged" if case.quick else f"judged at slip {DP_SLIP}"
axes[0][0].text(0.02, 0.02, f"load {ws.M_WHEEL * ws.G:.2f} N; {judged}", transform=axes[0][0].transAxes, fontsize=7)
ax = axes[1][0]
s_show = SLIPS[-1]
for kind, (fmt, c, name) in styles.items():
    if kind not in runs[s_show]:
        continue
    r = runs[s_show][kind]
    m = max(1, int(round(ws.grouser_period(s_show) / (r["t"][1] - r["t"][0]))))
    fx = np.convolve(r["fx"], np.ones(m) / m, mode="valid")
    ax.plot(r["t"][m - 1:], fx, "-", color=c, lw=1, label=f"{name}: drawbar pull")
    ax.plot(r["t"], (r["z0"] - r["z"]) * 1e3 / 10, "--", color=c, lw=0.8, label=f"{name}: sinkage / 10 (mm)")
ax.axvline(runs[s_show]["full"]["means"][5], color="k", lw=0.5, ls=":")
ax.set(xlabel="time since the wheel was released (s)", ylabel="N, or mm / 10",
       title=f"slip {s_show}: drawbar pull (mean over a grouser period) and sinkage")
ax.legend(fontsize=6)
ax = axes[1][1]
xs = np.arange(len(SLIPS))
ax.bar(xs - 0.2, [runs[s]["full"]["wall"] for s in SLIPS], 0.4, color="C0", label="whole bed")
ax.bar(xs + 0.2, [runs[s]["box"]["wall"] for s in SLIPS], 0.4, color="C3", label="active box")
ax.set_xticks(xs, [f"slip {s}" for s in SLIPS])
ax.set(ylabel="wall time of the stepping (s)",
       title=f"{bed['grains']} grains, {int(round(T_RUN / ws.DT))} steps a run ({case.backend})")
ax.legend(fontsize=7)
case.save(fig)
case.finish()
