"""A peer side by side: the paper's hopper discharged by the engine and by LIGGGHTS 3.8.

Set-up (validation/hopper_setup.py; paper s. 6.2.2, test ID 1): a hopper 0.20 m wide and 0.04 m deep
with a 0.04 x 0.04 m orifice spanning its depth; plastic spheres PS (r = 3 mm, rho = 1592 kg/m^3,
E = 10 MPa, nu = 0.35, CoR = 0.85, mu = 0.40, Crr = 0.04), dt = 20 us. The engine settles the grains
on the closed orifice (14,058 of them, about 0.36 m; 5,000, about 0.14 m, with --quick), writes the packing and the
floor, then opens the orifice; LIGGGHTS (Debian `liggghts`, validation/hopper_liggghts.in) starts from
the same packing with the orifice open: Hertz-Mindlin with history, CoR-derived damping and the
constant directional torque rolling friction, whose coefficient between two grains is doubled to give
the engine's torque (LIGGGHTS multiplies by R* = R/2, the engine by the contact arm, about R).
Both run 7.5 s (1.5 s with --quick); grains 5 cm below the floor leave and are counted.

Reference: LIGGGHTS 3.8 on the same set-up. Verdicts: the steady mass flow rate (slope of the
discharged mass between 20 % and 60 % discharged) and the mass fraction discharged at the end each
within 5 % of LIGGGHTS's.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from common import Case, import_deme  # noqa: E402
import hopper_setup as hs  # noqa: E402

case = Case("peer_hopper", __doc__)
case.require_liggghts()
deme = import_deme()
import numpy as np  # noqa: E402

n = 5000 if case.quick else 14058
t_end = 1.5 if case.quick else 7.5
sim, pos = hs.settled_hopper(deme, n, 0.45 if case.quick else 0.8)
folder = os.path.join(case.args.out, "peer_hopper_liggghts")
hs.write_peer_files(folder, pos)
t, frac = hs.discharge(sim, n, t_end)
rate = hs.steady_rate(t, frac, n)
print(f"engine: {n} grains, discharged {frac[-1] * 100:.1f} % in {t[-1]:.2f} s, steady rate {rate:.4f} kg/s")
tl, fl = hs.run_liggghts(folder, n, t_end)
rate_l = hs.steady_rate(tl, fl, n)
end_e, end_l = float(np.interp(t_end, t, frac)), float(np.interp(t_end, tl, fl))
print(f"LIGGGHTS: discharged {end_l * 100:.1f} % in {tl[-1]:.2f} s, steady rate {rate_l:.4f} kg/s")
src = "LIGGGHTS 3.8, same hopper, packing, model and time step"
case.check("steady mass flow rate, 20-60 % discharged (kg/s)", round(rate_l, 4), src, round(rate, 4), "5 %",
           math.isfinite(rate) and math.isfinite(rate_l) and abs(rate - rate_l) <= 0.05 * rate_l)
case.check(f"mass fraction discharged after {t_end:g} s", round(end_l, 4), src, round(end_e, 4), "5 %",
           abs(end_e - end_l) <= 0.05 * end_l)

fig, ax = case.figure(figsize=(6, 4.2))
ax.plot(t, frac, "-", color="C0", label=f"engine: {rate:.3f} kg/s over 20-60 %")
ax.plot(tl, fl, "--", color="C3", label=f"LIGGGHTS 3.8: {rate_l:.3f} kg/s")
ax.set(xlabel="time since the orifice opened (s)", ylabel="discharged mass fraction",
       title=f"hopper discharge, {n} plastic spheres")
ax.legend(fontsize=7)
case.save(fig)
case.finish()
