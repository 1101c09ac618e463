#!/usr/bin/env bash
# MIXER-LISTING: the paper's mixer listing in C++ (build/bench/mixer_listing) and in Python
# (bench/mixer_listing.py through build/python), the same scene and frames, run back to back in
# the order C++, Python, C++, Python, so that a drift of the machine's speed shows in both. Prints
# each run's JSON line, then one summary line: the Python loop's wall and CPU time over the C++
# one, pair by pair, and the time each spent outside DoDynamics (the listing's own
# per-frame work: output files, queries, prints; the Python binding's whole cost is in the
# difference of those, since the DoDynamics calls are the same C++ calls).
#   [PAIRS=2] bench/python_vs_cpp.sh [granular_rad = 0.02] [step = 2e-5] [frames = 6]
set -euo pipefail
cd "$(dirname "$0")/.."
args=("${1:-0.02}" "${2:-2e-5}" "${3:-6}")
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
lines=()
for round in $(seq "${PAIRS:-2}"); do
    lines+=("$(./build/bench/mixer_listing "$out/cpp" "${args[@]}" | grep '^{')")
    echo "${lines[-1]}"
    lines+=("$(PYTHONPATH=build/python /usr/bin/python3 bench/mixer_listing.py "$out/py" "${args[@]}" | grep '^{')")
    echo "${lines[-1]}"
done
printf '%s\n' "${lines[@]}" | /usr/bin/python3 -c '
import json, statistics, sys
runs = [json.loads(l) for l in sys.stdin]
cpp = [r for r in runs if r["lang"] == "cpp"]
py = [r for r in runs if r["lang"] == "python"]
med = lambda rs, k: statistics.median(r[k] for r in rs)
print(json.dumps({"bench": "mixer_listing_python_vs_cpp", "clumps": cpp[0]["clumps"], "frames": cpp[0]["frames"],
    "steps": cpp[0]["steps"], "cpp_loop_s": med(cpp, "loop_s"), "python_loop_s": med(py, "loop_s"),
    "python_over_cpp_wall": [round(p["loop_s"] / c["loop_s"] - 1, 4) for c, p in zip(cpp, py)],
    "python_over_cpp_cpu": [round(p["loop_cpu_s"] / c["loop_cpu_s"] - 1, 4) for c, p in zip(cpp, py)],
    "cpp_outside_dodynamics_s": med(cpp, "outside_dodynamics_s"),
    "python_outside_dodynamics_s": med(py, "outside_dodynamics_s"),
    "binding_cost_share": (med(py, "outside_dodynamics_s") - med(cpp, "outside_dodynamics_s")) / med(cpp, "loop_s"),
    # The same simulation in both (the C++ line prints 6 digits).
    "same_result": all("%.6g" % r["final_max_v"] == "%.6g" % cpp[0]["final_max_v"]
                       and r["final_contacts"] == cpp[0]["final_contacts"] for r in runs)}))
'
