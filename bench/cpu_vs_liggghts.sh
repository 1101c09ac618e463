#!/usr/bin/env bash
# CPU-BED side by side: this engine and LIGGGHTS 3.8 on the same bed, model, time step and step
# count, on this machine's cores, one after the other. Prints both JSON lines and the ratio.
#   usage: bench/cpu_vs_liggghts.sh [build dir]   (needs: apt-get install liggghts)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
shared="$here/../shared/bench"
ranks="$(nproc)"

command -v liggghts >/dev/null || { echo "liggghts not found: apt-get install liggghts" >&2; exit 1; }
[ -x "$build/bench/cpu_bed" ] || { echo "build the engine first: bash scripts/setup.sh" >&2; exit 1; }

ours="$("$build/bench/cpu_bed" "$shared/bed60k.csv" 200 2000)"
echo "$ours"

log="$(mktemp)"
(cd "$shared" && mpirun --allow-run-as-root -np "$ranks" liggghts -in liggghts_bed.in -var data bed60k.data \
    -var nwarm 200 -var nrun 2000 -log none >"$log" 2>&1)
loop="$(grep 'Loop time' "$log" | tail -n 1 | awk '{print $4}')"
neigh="$(grep 'Ave neighs/atom' "$log" | tail -n 1 | awk '{print $NF}')"
rm -f "$log"
ligg_rate="$(awk -v t="$loop" 'BEGIN { printf "%.6g", 60000 * 2000 / t }')"
echo "{\"case\": \"CPU-BED\", \"size\": 60000, \"backend\": \"liggghts-3.8-mpi$ranks\", \"spheres\": 60000, \"neighbours_per_atom\": $neigh, \"steps\": 2000, \"wall_s\": $loop, \"sphere_steps_per_s\": $ligg_rate}"

our_rate="$(echo "$ours" | sed -E 's/.*"sphere_steps_per_s": ([0-9.e+]+).*/\1/')"
awk -v a="$our_rate" -v b="$ligg_rate" 'BEGIN { printf "ratio (this engine / LIGGGHTS): %.2f\n", a / b }'
