#!/usr/bin/env bash
# GPU test run (on a machine with an NVIDIA GPU; see docs/gpu-tests.md): builds with the CUDA backend,
# runs the CUDA unit tests, the whole suite with DEME_BACKEND=cuda, and the CPU/GPU parity tests.
# Logs go to $OUT (default ./gpu-test-out).
#   tests/gpu/run.sh [build|unit|suite|output|bench|timing|gpus|settled|profile|compile|filter ...]   (default: build unit suite)
set -uo pipefail
cd "$(dirname "$0")/../.."
OUT="${OUT:-$PWD/gpu-test-out}"
mkdir -p "$OUT"
steps=("$@")
[ ${#steps[@]} -eq 0 ] && steps=(build unit suite)
export DEME_CACHE_DIR="${DEME_CACHE_DIR:-/tmp/deme-kernel-cache}"
jobs="$(nproc)"

for step in "${steps[@]}"; do
    case "$step" in
    build)
        nvidia-smi >"$OUT/nvidia-smi.txt" 2>&1
        cmake -S . -B build-gpu -DCMAKE_BUILD_TYPE=Release -DDEME_ENABLE_CUDA=ON >"$OUT/configure.log" 2>&1 &&
            cmake --build build-gpu -j"$jobs" >"$OUT/build.log" 2>&1 || {
            tail -n 60 "$OUT/build.log"
            exit 1
        }
        echo "build: ok"
        ;;
    unit)
        ./build-gpu/tests/deme_tests --gtest_filter='Cuda*:GpuParity*' >"$OUT/unit.log" 2>&1
        echo "unit: rc $? ($(grep -c '^\[       OK' "$OUT/unit.log") ok, $(grep -c '^\[  FAILED  \]' "$OUT/unit.log") failed lines)"
        grep -E '^\[  FAILED|^\[  SKIPPED' "$OUT/unit.log" | head -20
        ;;
    suite)
        # Async.* pin themselves to the CPU (2-2.5 minutes each there, run by CI anyway): left out, so
        # the suite fits one 10-minute command.
        DEME_BACKEND=cuda ctest --test-dir build-gpu -j8 -E 'tsan|package|^Async\.' --timeout 400 \
            >"$OUT/suite.log" 2>&1
        echo "suite (DEME_BACKEND=cuda): rc $?"
        grep -E 'tests passed|\(Failed\)|\(Timeout\)|\(SEGFAULT\)|Exception' "$OUT/suite.log" | head -40
        ;;
    bench)
        obj=.benchdata/internal_mixer.obj
        for r in 0.004 0.0025 0.0015; do
            for kind in spheres clumps; do
                timeout "${BENCH_TIMEOUT:-300}" ./build-gpu/bench/mixer "$obj" "$r" "$kind" 2000 2000 2>&1 | tee -a "$OUT/bench.jsonl" | tail -n 3
            done
        done
        ;;
    gpus)
        # One GPU against two (detection on the second), asynchronous detection, MIXER-BENCH at r = 4 mm:
        # fresh (2000 + 2000 steps) spheres and clumps, then the settled spheres.
        for g in 1 2; do
            for kind in spheres clumps; do
                timeout 120 ./build-gpu/bench/mixer .benchdata/internal_mixer.obj 0.004 $kind 2000 2000 5e-7 $g async 2>&1 |
                    tee -a "$OUT/gpus.jsonl" | tail -n 2
            done
        done
        for g in 1 2; do
            timeout 200 ./build-gpu/bench/mixer .benchdata/internal_mixer.obj 0.004 spheres 125000 2000 2e-6 $g async 2>&1 |
                tee -a "$OUT/gpus.jsonl" | tail -n 2
        done
        ;;
    timing)
        # The phase timings (kinematics' binning and pair search, dynamics' force pass...) and the
        # collaboration counters of the early mixer at r = 4 mm, asynchronous and synchronous.
        for kind in ${TIMING_KINDS:-spheres clumps}; do
            for mode in async sync; do
                DEME_BENCH_TIMING=1 timeout 120 ./build-gpu/bench/mixer .benchdata/internal_mixer.obj 0.004 $kind 2000 2000 5e-7 1 $mode \
                    >>"$OUT/timing.log" 2>&1
                echo "timing $kind $mode: rc $?"
            done
        done
        grep -E '^\{' "$OUT/timing.log" | cut -c1-400
        ;;
    settled)
        # The settled variant: 0.25 s of mixing as 125000 warm-up steps of 2e-6 s (the grains land on
        # the floor), then 2000 timed steps of 5e-7 s. SETTLED="r:kind[:mode] ..." picks the cases
        # (mode auto, sync or async; auto by default).
        for spec in ${SETTLED:-0.004:spheres 0.004:clumps}; do
            IFS=: read -r r kind mode <<<"$spec"
            timeout "${SETTLED_TIMEOUT:-550}" ./build-gpu/bench/mixer .benchdata/internal_mixer.obj "$r" "$kind" 125000 2000 2e-6 1 "${mode:-auto}" 2>&1 |
                tee -a "$OUT/settled.jsonl" | tail -n 3
        done
        ;;
    profile)
        # Nsight Compute counters of every kernel of a few steps of the settled mixer (r = 4 mm): the
        # capture starts after the warm-up (DEME_CUDA_PROFILE_FROM_STEP), so the warm-up runs at speed.
        DEME_CUDA_PROFILE_FROM_STEP=125001 timeout 550 ncu --profile-from-start off --launch-count 40 --csv \
            --metrics gpu__time_duration.sum,dram__bytes_read.sum,dram__bytes_write.sum,dram__throughput.avg.pct_of_peak_sustained_elapsed \
            ./build-gpu/bench/mixer .benchdata/internal_mixer.obj 0.004 spheres 125000 4 2e-6 >"$OUT/ncu.csv" 2>"$OUT/ncu.err"
        echo "profile: rc $? ($(wc -l <"$OUT/ncu.csv") lines)"
        tail -n 5 "$OUT/ncu.err"
        ;;
    compile)
        # A custom force model's Initialize cost on the GPU backend (NVRTC plus the host build).
        ./build-gpu/bench/model_compile - cuda 2>&1 | tee -a "$OUT/compile.jsonl" | tail -n 3
        ;;
    output)
        # The output tests on the GPU backend: VTU files read back by meshio against the CSV, the
        # .pvd series, failed writes, snapshots read by PIL; the writers read the state the device
        # has moved on to (downloaded on demand). Needs Debian's python3-meshio and python3-pil.
        /usr/bin/python3 -c "import meshio, PIL" 2>/dev/null ||
            echo "output: /usr/bin/python3 lacks meshio or PIL (apt-get install python3-meshio python3-pil): the read-back tests will fail"
        DEME_BACKEND=cuda ./build-gpu/tests/deme_tests --gtest_filter='VtuOutput*:OutputFailure*:Snapshot*:Output.*:ProgressReport.Callback*' \
            >"$OUT/output.log" 2>&1
        echo "output (DEME_BACKEND=cuda): rc $? ($(grep -c '^\[       OK' "$OUT/output.log") ok)"
        grep -E '^\[  FAILED|^\[  SKIPPED' "$OUT/output.log" | head -20
        timeout 300 ./build-gpu/bench/output_write solver 1000000 /tmp 2>&1 | tee -a "$OUT/output.jsonl" | tail -n 2
        ;;
    filter)
        # DEME_BACKEND=cuda on the gtest filter in FILTER.
        DEME_BACKEND=cuda ./build-gpu/tests/deme_tests --gtest_filter="$FILTER" >"$OUT/filter.log" 2>&1
        echo "filter $FILTER: rc $? ($(grep -c '^\[       OK' "$OUT/filter.log") ok)"
        grep -E '^\[  FAILED|^\[  SKIPPED' "$OUT/filter.log" | head -20
        ;;
    *)
        echo "unknown step $step" >&2
        exit 2
        ;;
    esac
done
