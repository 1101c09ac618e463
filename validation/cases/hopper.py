"""Discharge of a flat-bottomed silo through a circular orifice against Beverloo's law (paper s. 6.2.2).

Set-up (validation/silo_setup.py): the grains of the paper's hopper test ID 1, plastic spheres PS
(r = 3 mm, d = 6 mm, rho = 1592 kg/m^3, E = 10 MPa, nu = 0.35, CoR = 0.85, mu = 0.40, Crr = 0.04,
dt = 20 us), poured into a cylindrical silo of their material and settled on the closed orifice, a
circular hole of the paper's 0.04 m in the middle of the floor, which then opens; grains that leave
(5 cm below the floor) are removed and their mass counted. Full: a silo 0.16 m across (four orifice
diameters), 18,400 grains (about 0.18 m of fill); --quick: 0.10 m across (2.5 orifice diameters,
the least for which the walls do not change the rate, Nedderman 1992, "Statics and kinematics of
granular materials", ch. 10), 4,200 grains (about 0.11 m); both until 62 % has left (about 9 s and
2 s).

Why a silo and not the paper's hopper: Beverloo's law was fitted to circular orifices in the floors
of cylindrical bins. The paper's hopper (0.20 x 0.04 m, a 0.04 x 0.04 m orifice spanning its depth)
has a slot between its side walls: there the law with D_h = 0.04 m, the orifice's hydraulic
diameter, gives 0.26 kg/s where the engine and LIGGGHTS 3.8 on the same hopper from the same packing
both discharge 0.49 kg/s (validation/README.md, "hopper"); that hopper is judged against LIGGGHTS
in peer_hopper.

Full runs also discharge the paper's hopper itself for its test IDs 1 (14,058 plastic spheres PS,
mu 0.40, Crr 0.04) and 2 (20,014 wooden cylinders WC as 5-sphere clumps, mu 0.70, Crr 0.07; both
settled from a loose pour for 0.8 s, then 7.5 s open; validation/hopper_setup.py), drawn as the
discharged mass fraction against time (not judged: the paper compares them with measurements of
Jian et al. 2023 that are not in our data; peer_hopper judges test ID 1 against LIGGGHTS).
HOPPER_PAPER=0 leaves them out, HOPPER_PAPER=1 or 2 takes one (on the CPU, test ID 2's 100,070
spheres take hours; on one H100 both IDs take about 100 s), and HOPPER_SILO=0 leaves the silo out
(the case is then recorded as skipped: no verdict). Each test ID's curve is kept in
<out>/hopper_paper_<id>.json, rewritten every frame (a run cut short keeps what it reached), and
<out>/hopper_paper.png draws every such file in the folder: runs of separate commands draw together.

Reference: Beverloo, Leniger & van de Velde (1961), Chem. Eng. Sci. 15, 260:
W = C rho_bulk sqrt(g) (D0 - k d)^(5/2), C = 0.58, k = 1.5, rho_bulk the settled bed's bulk density
(measured in its middle). Verdict: the steady rate (the slope of the discharged mass between 20 % and
60 % discharged) within 20 % of W.
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from common import Case, commit, import_deme, write_json  # noqa: E402
import hopper_setup as hs  # noqa: E402
import silo_setup as ss  # noqa: E402

case = Case("hopper", __doc__)
deme = import_deme()
import numpy as np  # noqa: E402

ORIFICE = 0.04
PAPER_IDS = {"1": ("test ID 1, PS spheres", 14058, hs.settled_hopper, hs.MASS),
             "2": ("test ID 2, WC cylinders (5-sphere clumps)", 20014, hs.settled_cylinder_hopper, hs.WC_MASS)}


def paper_file(run_id):
    return os.path.join(case.args.out, f"hopper_paper_{run_id}.json")


def discharge_paper_hopper(run_id):
    """Settles and discharges the paper's hopper for one test ID, its curve kept in paper_file(run_id)."""
    label, count, build, grain_mass = PAPER_IDS[run_id]
    psim, ppos = build(deme, count, 0.8)
    record = {"label": label, "grains": count, "fill": float(ppos[:, 2].max()), "backend": case.backend,
              "commit": commit(), "t": [], "fraction": [], "rate": None}

    def keep(t, frac):
        record["t"], record["fraction"] = [float(x) for x in t], [float(x) for x in frac]
        rate = hs.steady_rate(np.array(t), np.array(frac), count, grain_mass)
        record["rate"] = rate if math.isfinite(rate) else None  # None until 60 % has left
        write_json(paper_file(run_id), record)

    pt, pfrac = hs.discharge(psim, count, 7.5, grain_mass=grain_mass, on_frame=keep)
    keep(pt, pfrac)
    print(f"the paper's hopper, {label}: {count} grains, fill {record['fill']:.3f} m, discharged "
          f"{pfrac[-1] * 100:.1f} % in {pt[-1]:.2f} s, steady rate {record['rate']} kg/s", flush=True)


def draw_paper_hopper():
    """<out>/hopper_paper.png: every test ID's curve kept in the out folder, with its origin."""
    runs = []
    for run_id in sorted(PAPER_IDS):
        if os.path.exists(paper_file(run_id)):
            with open(paper_file(run_id)) as f:
                runs.append(json.load(f))
    if not runs:
        return
    fig, ax = case.figure(1, 1, figsize=(6.5, 4.2))
    for k, r in enumerate(runs):
        rate = "under 60 % discharged" if r["rate"] is None else f"{r['rate']:.3f} kg/s over 20-60 %"
        ax.plot(r["t"], r["fraction"], "-", color=f"C{k}",
                label=f"{r['label']}, {r['grains']} grains: {rate} ({r['backend']}, {r['commit']})")
    ax.set(xlabel="time since the orifice opened (s)", ylabel="discharged mass fraction",
           title="the paper's hopper, 0.20 x 0.04 m, orifice 0.04 m (not judged)")
    ax.legend(fontsize=7)
    origins = sorted({f"{r['backend']}, {r['commit']}" for r in runs})
    case.save(fig, origin="; ".join(origins), name="hopper_paper")


# HOPPER_PAPER: which of the paper's test IDs the full run discharges ("1,2", the default; "0": none).
paper_ids = [] if case.quick else [i for i in os.environ.get("HOPPER_PAPER", "1,2").split(",") if i in PAPER_IDS]
if os.environ.get("HOPPER_SILO", "1") == "0":
    for run_id in paper_ids:
        discharge_paper_hopper(run_id)
    draw_paper_hopper()
    case.finish(skipped="the silo left out (HOPPER_SILO=0): no verdict; the paper's hopper drawn")

if case.quick:
    n, diameter, t_end, stop = 4200, 0.10, 2.5, 0.62
else:
    n, diameter, t_end, stop = 18400, 0.16, 10.0, 0.62
silo = ss.Silo(deme, n, diameter, ORIFICE)
t_settle = silo.settle()
fill, rho_bulk = silo.measure()
print(f"settled: {n} grains in {t_settle:.2f} s, fill height {fill:.3f} m, bulk density {rho_bulk:.0f} kg/m^3 "
      f"(solid fraction {rho_bulk / hs.RHO:.3f})", flush=True)
t, frac = silo.discharge(t_end, stop)
rate, law = hs.steady_rate(t, frac, n), ss.beverloo(rho_bulk, ORIFICE)
print(f"discharged {frac[-1] * 100:.1f} % in {t[-1]:.2f} s; steady rate {rate:.4f} kg/s, Beverloo {law:.4f} kg/s "
      f"({(rate / law - 1) * 100:+.1f} %)")
case.check(f"steady mass flow rate, 20-60 % discharged (kg/s; D0 = {ORIFICE} m, silo {diameter} m)", round(law, 4),
           f"Beverloo et al. (1961), C = 0.58, k = 1.5, measured bulk density {rho_bulk:.0f} kg/m^3",
           round(rate, 4), "20 %", math.isfinite(rate) and abs(rate - law) <= 0.2 * law)

for run_id in paper_ids:
    discharge_paper_hopper(run_id)
draw_paper_hopper()

fig, axes = case.figure(1, 2, figsize=(11, 4.2))
ax, ax2 = axes[0], axes[1]
mass = frac * n * hs.MASS
ax.plot(t, frac, "-", color="C0", label="engine")
w = (frac >= 0.2) & (frac <= 0.6)
ax.axhspan(0.2, 0.6, color="gray", alpha=0.12, label="20-60 %: the steady rate's window")
ax.set(xlabel="time since the orifice opened (s)", ylabel="discharged mass fraction",
       title=f"silo {diameter * 100:g} cm across, orifice {ORIFICE * 100:g} cm, {n} spheres")
ax.legend(fontsize=7)
ax2.plot(t, mass, "-", color="C0", label=f"engine: {rate:.3f} kg/s over 20-60 %")
if np.count_nonzero(w) >= 2:
    t_mid = float(np.mean(t[w]))
    m_mid = float(np.interp(t_mid, t, mass))
    span = np.array([t[w][0] - 0.3, t[w][-1] + 0.3])
    ax2.plot(span, m_mid + law * (span - t_mid), "k--", label=f"Beverloo: {law:.3f} kg/s")
    ax2.fill_between(span, m_mid + 0.8 * law * (span - t_mid), m_mid + 1.2 * law * (span - t_mid), color="gray",
                     alpha=0.15, label="Beverloo +- 20 %")
ax2.set(xlabel="time since the orifice opened (s)", ylabel="discharged mass (kg)")
ax2.legend(fontsize=7)
case.save(fig)
case.finish()
