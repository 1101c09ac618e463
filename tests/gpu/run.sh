#!/usr/bin/env bash
# GPU test run (on a machine with an NVIDIA GPU; see docs/gpu-tests.md): builds with the CUDA backend,
# runs the CUDA unit tests and the CPU/GPU comparisons (GpuParity.*), and the cuda instances of the
# backend tests (Suite.Name/cuda, tests/BackendFixture.h); their CPU instances are CI's.
# Logs go to $OUT (default ./gpu-test-out).
#   tests/gpu/run.sh [build|baseline|unit|suite|pooled|slabs|pooledab|python|output|bench|small|sweep|graphsteps|smallab|discharge|mixerab|profile-small|profile-step|activebox|profile-box|memory|shear|chute|timing|gpus|earlyab|settled|profile|compile|validation|filter ...]
#   (default: build unit suite python)
set -uo pipefail
cd "$(dirname "$0")/../.."
OUT="${OUT:-$PWD/gpu-test-out}"
mkdir -p "$OUT"
steps=("$@")
[ ${#steps[@]} -eq 0 ] && steps=(build unit suite python)
export DEME_CACHE_DIR="${DEME_CACHE_DIR:-/tmp/deme-kernel-cache}"
jobs="$(nproc)"

# The Python module's interpreter: /usr/bin/python3 where it has numpy and pybind11 is found;
# otherwise the Debian packages carried in .pydebs/ (tests/gpu/python-deps.sh), unpacked into a prefix
# of this checkout (never into /) and run through a wrapper that sets PYTHONHOME and the library path
# for that interpreter only (exported for the whole script they would break the machine's own Python,
# which CMake's configure runs).
PY=/usr/bin/python3
PY_CMAKE_ARGS=()
if [ -d .pydebs ] && ! { /usr/bin/python3 -c "import numpy" 2>/dev/null && [ -d /usr/lib/cmake/pybind11 ]; }; then
    prefix="$PWD/.pyprefix"
    if [ ! -x "$prefix/usr/bin/python3.11" ]; then
        mkdir -p "$prefix"
        for f in .pydebs/*.deb; do dpkg -x "$f" "$prefix"; done
    fi
    # Debian's matplotlib looks for its data beside itself, then at the absolute /usr/share path, and
    # for its rc file only at /etc/matplotlibrc (or $MATPLOTLIBRC): point both at the prefix's copies.
    mpl="$prefix/usr/lib/python3/dist-packages/matplotlib"
    [ -d "$mpl" ] && [ ! -e "$mpl/mpl-data" ] && ln -s "$prefix/usr/share/matplotlib/mpl-data" "$mpl/mpl-data"
    multiarch="$prefix/usr/lib/x86_64-linux-gnu"
    cat >"$prefix/python3" <<WRAPPER
#!/bin/sh
export PYTHONHOME="$prefix/usr"
export MATPLOTLIBRC="$prefix/usr/share/matplotlib/mpl-data/matplotlibrc"
export LD_LIBRARY_PATH="$multiarch:$multiarch/blas:$multiarch/lapack\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
exec "$prefix/usr/bin/python3.11" "\$@"
WRAPPER
    chmod +x "$prefix/python3"
    PY="$prefix/python3"
    PY_CMAKE_ARGS=(-DPython3_EXECUTABLE="$PY" -Dpybind11_DIR="$prefix/usr/lib/cmake/pybind11")
fi

# Configures build-gpu/ and builds it (the arguments go to `cmake --build`, e.g. a target); on a
# failure the build log's end, and the script stops.
build_gpu() {
    cmake -S . -B build-gpu -DCMAKE_BUILD_TYPE=Release -DDEME_ENABLE_CUDA=ON "${PY_CMAKE_ARGS[@]}" >"$OUT/configure.log" 2>&1 &&
        cmake --build build-gpu -j"$jobs" "$@" >"$OUT/build.log" 2>&1 || {
        tail -n 60 "$OUT/build.log"
        exit 1
    }
}

for step in "${steps[@]}"; do
    case "$step" in
    build)
        nvidia-smi >"$OUT/nvidia-smi.txt" 2>&1
        build_gpu
        echo "build: ok"
        ;;
    build-module)
        # The Python module alone (what validation/run.py needs), without the tests and benchmarks:
        # a validation run on a fresh machine starts a few minutes sooner.
        build_gpu --target _deme
        echo "build-module: ok"
        ;;
    baseline)
        # An earlier commit's source in $BASE (default .base, e.g. `git archive <commit> | tar -x -C
        # .base`, ignored and carried), its mixer benchmark built beside, for before/after runs in one
        # command (`MIXERS=".base/build-gpu/bench/mixer ./build-gpu/bench/mixer" tests/gpu/run.sh settled`).
        base="${BASE:-.base}"
        # A tree carried as $base/tree.tar.xz (`git archive <commit> src include bench cmake
        # CMakeLists.txt data | xz > .base/tree.tar.xz`: a few hundred kB, where the carried paths
        # must stay under the device tool's 64 MiB) is unpacked in place first.
        [ -f "$base/tree.tar.xz" ] && tar -xJf "$base/tree.tar.xz" -C "$base"
        (cmake -S "$base" -B "$base/build-gpu" -DCMAKE_BUILD_TYPE=Release -DDEME_ENABLE_CUDA=ON -DDEME_BUILD_TESTS=OFF -DDEME_BUILD_PYTHON=OFF \
            -DDEME_BUILD_DEMOS=OFF && cmake --build "$base/build-gpu" -j"$jobs" --target mixer) >"$OUT/baseline-build.log" 2>&1 || {
            tail -n 40 "$OUT/baseline-build.log"
            exit 1
        }
        # SMALL-SYSTEMS exists from the issue "Small systems fast on the GPU" on: an older baseline
        # (for MIXER-BENCH before that issue) goes without it.
        cmake --build "$base/build-gpu" -j"$jobs" --target small_systems >>"$OUT/baseline-build.log" 2>&1 ||
            echo "baseline: no small_systems target"
        # DISCHARGE exists from 354e84f on: an older baseline goes without it (or copy
        # bench/discharge.cpp and its CMake lines into the baseline's tree first).
        cmake --build "$base/build-gpu" -j"$jobs" --target discharge >>"$OUT/baseline-build.log" 2>&1 ||
            echo "baseline: no discharge target"
        echo "baseline build: ok"
        ;;
    unit)
        ./build-gpu/tests/deme_tests --gtest_filter='Cuda*:GpuParity*' >"$OUT/unit.log" 2>&1
        echo "unit: rc $? ($(grep -c '^\[       OK' "$OUT/unit.log") ok, $(grep -c '^\[  FAILED  \]' "$OUT/unit.log") failed lines)"
        grep -E '^\[  FAILED|^\[  SKIPPED' "$OUT/unit.log" | head -20
        ;;
    suite)
        # Every backend test's cuda instance (each instance sets DEME_BACKEND for its solvers), and the
        # demos with DEME_BACKEND=cuda. Left to CI, so that the step fits one 10-minute command: the
        # CPU instances, the CPU's bit-for-bit tests (Async.*, Determinism.*, RunMonitor.*,
        # ForceModelBitIdentity.*), the tests that start no simulation, TSAN and package tests.
        # GpuParity.* (whose CPU halves are the slowest tests here) run in the unit step.
        # SUITE_EXCLUDE (a ctest regex) leaves tests out, e.g. the slowest ones when a command is short.
        DEME_BACKEND=cuda ctest --test-dir build-gpu -j"${SUITE_JOBS:-8}" -R '/cuda$|^demo_' ${SUITE_EXCLUDE:+-E "$SUITE_EXCLUDE"} \
            --timeout 400 --output-on-failure >"$OUT/suite.log" 2>&1
        echo "suite (cuda instances and demos): rc $?"
        grep -E 'tests passed|\(Failed\)|\(Timeout\)|\(SEGFAULT\)|Exception' "$OUT/suite.log" | head -40
        ;;
    pooled)
        # The suite's step with every contact set's history pooled and no spare slot in any pool
        # (state/HistoryPool.h): each pair that begins to touch pauses its step for the pool to grow.
        DEME_POOLED_HISTORY=1 DEME_HISTORY_POOL_SPARE=0 DEME_BACKEND=cuda ctest --test-dir build-gpu -j"${SUITE_JOBS:-8}" \
            -R '/cuda$|^demo_' ${SUITE_EXCLUDE:+-E "$SUITE_EXCLUDE"} --timeout 400 --output-on-failure >"$OUT/pooled.log" 2>&1
        echo "pooled suite (cuda instances and demos, every history pooled, no spare slot): rc $?"
        grep -E 'tests passed|\(Failed\)|\(Timeout\)|\(SEGFAULT\)|Exception' "$OUT/pooled.log" | head -40
        ;;
    slabs)
        # The suite's step with every detection that bins spheres by their centres made in 3 slabs of
        # bin layers (runtime/DetectionSlabs.h; at lab scale detection bins by boxes, and searches a
        # sphere with several threads: here by centres and a thread a sphere, as at scale).
        DEME_CUDA_CENTRE_BINNING=1 DEME_CUDA_SEARCH_LANES=1 DEME_CUDA_WIDE_SPHERES=0 DEME_DETECTION_SLABS=3 \
            DEME_BACKEND=cuda ctest --test-dir build-gpu -j"${SUITE_JOBS:-8}" -R '/cuda$|^demo_' \
            ${SUITE_EXCLUDE:+-E "$SUITE_EXCLUDE"} --timeout 400 --output-on-failure >"$OUT/slabs.log" 2>&1
        echo "slabs suite (cuda instances and demos, detection in 3 slabs where spheres bin by centres): rc $?"
        grep -E 'tests passed|\(Failed\)|\(Timeout\)|\(SEGFAULT\)|Exception' "$OUT/slabs.log" | head -40
        ;;
    pooledab)
        # The settled mixer (the `settled` step's command, r = POOLED_R, default 0.004) with every
        # contact set dense and with every set pooled (DEME_POOLED_HISTORY=0 and 1), alternating,
        # POOLED_ROUNDS times (default 2): the pooled pass's speed against the dense one's.
        for k in $(seq "${POOLED_ROUNDS:-2}"); do
            for m in 0 1; do
                DEME_BENCH_TIMING=1 DEME_POOLED_HISTORY=$m timeout "${SETTLED_TIMEOUT:-200}" ./build-gpu/bench/mixer \
                    .benchdata/internal_mixer.obj "${POOLED_R:-0.004}" spheres 125000 2000 2e-6 1 auto >"$OUT/pooledab-$m-$k.txt" 2>&1
                echo "pooled $m round $k: $(grep -o '"sphere_steps_per_s": [0-9.e+]*' "$OUT/pooledab-$m-$k.txt")" \
                    "$(grep -o '"device_bytes_per_sphere": [0-9.e+]*' "$OUT/pooledab-$m-$k.txt")" \
                    "$(grep -o 'pooled in [0-9]* of [0-9]* installed sets, [0-9]* steps' "$OUT/pooledab-$m-$k.txt" | tail -1)"
            done
        done
        ;;
    python)
        # The Python module built in build-gpu (the build step builds it where pybind11 and numpy
        # are found): its pytest suite and the paper's Python listing (demos/python/mixer.py, two
        # steps), both with DEME_BACKEND=cuda. The installed-package and pip tests are left out
        # (they rebuild on the CPU and test packaging, not the backend).
        if ! ls build-gpu/python/deme/_deme*.so >/dev/null 2>&1; then
            echo "python: module not built in build-gpu ($(grep -h 'Python module' "$OUT/configure.log" 2>/dev/null || echo 'see configure.log'))"
            continue
        fi
        DEME_BACKEND=cuda PYTHONPATH="$PWD/build-gpu/python" DEME_TEST_SOURCE_DIR="$PWD" \
            DEME_CACHE_DIR="$DEME_CACHE_DIR" "$PY" -m pytest -v -p no:cacheprovider python/tests \
            -k 'not installed_package and not cpp_install' >"$OUT/python.log" 2>&1
        echo "python tests (DEME_BACKEND=cuda): rc $? ($(tail -n 1 "$OUT/python.log"))"
        grep -E 'FAILED|ERROR' "$OUT/python.log" | head -20
        mkdir -p "$OUT/python-listing"
        (cd "$OUT/python-listing" && DEME_BACKEND=cuda PYTHONPATH="$OLDPWD/build-gpu/python" \
            "$PY" "$OLDPWD/demos/python/mixer.py" --quick >listing.log 2>&1)
        echo "python listing (DEME_BACKEND=cuda): rc $? ($(grep -c '^Frame' "$OUT/python-listing/listing.log") frame(s); $(grep -m1 -o 'CUDA backend[^;]*\|CPU backend[^;]*' "$OUT/python-listing/listing.log"))"
        rm -f "$OUT"/python-listing/DemoOutput_Mixer/*.csv
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
    activebox)
        # ACTIVE-BOX on the GPU: 10^6 packed grains, whole bed active (2,000 steps) against 5 % active
        # (10,000 steps), then the ratio.
        # ACTIVEBOX_RUNS runs (default 3, for a median), then, with ACTIVEBOX_TIMING=1, one run per
        # detection mode with the phase timings and the threads' collaboration counts.
        for i in $(seq "${ACTIVEBOX_RUNS:-3}"); do
            timeout 200 ./build-gpu/bench/active_box cuda 1000000 0.05 2000 10000 2>&1 | tee -a "$OUT/activebox.jsonl" | tail -n 1
        done
        if [ "${ACTIVEBOX_TIMING:-0}" = 1 ]; then
            for mode in sync async; do
                DEME_BENCH_TIMING=1 timeout 200 ./build-gpu/bench/active_box cuda 1000000 0.05 2000 10000 $mode \
                    >>"$OUT/activebox-timing.log" 2>&1
                echo "activebox timing $mode: rc $?"
            done
        fi
        ;;
    memory)
        # Memory by array group (docs/memory.md) of MIXER-BENCH early spheres: MEMORY_R lists the radii
        # (default 0.004 and 0.001, 0.70 M and 45.8 M spheres), 20 steps each after Initialize, with
        # the table ShowMemoryStats prints. MEMORY_MODE: the detection mode (auto, the default; sync
        # or async); MEMORY_STEPS: the steps (default 20, one detection; 60 take three); MEMORY_TIMEOUT:
        # seconds a radius may take (default 500). A billion spheres on one H200 (docs/memory.md), in a
        # command of its own after one that built build-gpu: MEMORY_R=0.000358 MEMORY_STEPS=200
        # MEMORY_MODE=sync MEMORY_TIMEOUT=580 tests/gpu/run.sh memory.
        for r in ${MEMORY_R:-0.004 0.001}; do
            DEME_BENCH_TIMING=1 timeout "${MEMORY_TIMEOUT:-500}" ./build-gpu/bench/mixer .benchdata/internal_mixer.obj "$r" spheres 0 \
                "${MEMORY_STEPS:-20}" 5e-7 1 \
                "${MEMORY_MODE:-auto}" >>"$OUT/memory.log" 2>&1
            echo "memory r = $r: rc $?"
        done
        ;;
    shear)
        # mu(I) in a sheared periodic cell (docs/periodic.md): DEMdemo_SimpleShear on the GPU.
        DEME_BACKEND=cuda timeout 500 ./build-gpu/demos/DEMdemo_SimpleShear /tmp/deme-shear >"$OUT/shear.log" 2>&1
        echo "shear: rc $?"; tail -n 3 "$OUT/shear.log"
        ;;
    chute)
        # The chute flow to a steady state (CHUTE_TIME seconds of flow, default 16; CHUTE_WIDTH, default
        # 2) on the GPU: its Bagnold exponent, steadiness and stress ratio, a failed check exit status 1
        # (docs/periodic.md).
        DEME_BACKEND=cuda timeout 550 ./build-gpu/demos/DEMdemo_ChuteFlow /tmp/deme-chute --time "${CHUTE_TIME:-16}" \
            --width "${CHUTE_WIDTH:-2}" >"$OUT/chute.log" 2>&1
        echo "chute: rc $?"; grep -v ETA "$OUT/chute.log" | grep -i "bagnold\|steady\|shear/normal\|wall time"
        ;;
    profile-box)
        # Nsight Compute: every kernel of some active-box steps (one whole-bed step first, so that the
        # capture starts in the box case; launched one by one, synchronous detection). PROFILE_LAUNCHES
        # kernels (default 120; about 1,000 take in a detection).
        DEME_CUDA_GRAPHS=0 DEME_CUDA_PROFILE_FROM_STEP=300 timeout 300 ncu --profile-from-start off --clock-control none \
            --launch-count "${PROFILE_LAUNCHES:-120}" --csv \
            --metrics gpu__time_duration.sum,dram__bytes_read.sum,dram__bytes_write.sum,launch__grid_size,launch__block_size,launch__registers_per_thread \
            ./build-gpu/bench/active_box cuda 1000000 0.05 1 600 sync >"$OUT/ncu-box.csv" 2>"$OUT/ncu-box.err"
        echo "profile-box: rc $? ($(wc -l <"$OUT/ncu-box.csv") lines)"
        ;;
    small)
        # SMALL-SYSTEMS on the GPU: the drum and the impact (default warm-up and timed steps), with
        # the phase timings, each in both detection modes; then the drum with its steps launched
        # kernel by kernel instead of replayed from step graphs (DEME_CUDA_GRAPHS=0).
        # SMALL_BIN lists the benchmark binaries (a baseline's and this build's, same command).
        for bin in ${SMALL_BIN:-./build-gpu/bench/small_systems}; do
            echo "{\"binary\": \"$bin\"}" >>"$OUT/small.log"
            for c in drum impact; do
                for mode in sync async; do
                    DEME_BENCH_TIMING=1 timeout 200 "$bin" $c "" "" cuda $mode >>"$OUT/small.log" 2>&1
                    echo "small $bin $c $mode: rc $?"
                done
            done
        done
        DEME_CUDA_GRAPHS=0 DEME_BENCH_TIMING=1 timeout 200 ./build-gpu/bench/small_systems drum "" "" cuda async >>"$OUT/small.log" 2>&1
        echo "small drum async, no graphs: rc $?"
        grep -E '^\{' "$OUT/small.log" | cut -c1-300
        ;;
    graphsteps)
        # SMALL-SYSTEMS, asynchronous detection, with graphs of GRAPH_STEPS steps (default 1, 8 and
        # 32; 1 is a graph per step), each setting twice, alternating, in one command.
        for round in 1 2; do
            for c in drum impact; do
                for k in ${GRAPH_STEPS:-1 8 32}; do
                    echo "{\"graph_steps\": $k, \"round\": $round}" >>"$OUT/graphsteps.log"
                    DEME_CUDA_GRAPH_STEPS=$k DEME_BENCH_TIMING=1 timeout 200 ./build-gpu/bench/small_systems $c "" "" cuda async \
                        >>"$OUT/graphsteps.log" 2>&1
                    echo "graphsteps $c $k round $round: rc $?"
                done
            done
        done
        grep -E "^\{" "$OUT/graphsteps.log" | cut -c1-330
        ;;
    discharge)
        # DISCHARGE (bench/discharge.cpp): a hopper emptying under the "remove" exit policy, 16,000
        # grains, 0.5 s from the first exit; DISCHARGE_BIN lists the binaries (a baseline's and this
        # build's), each run twice, alternating.
        for round in 1 2; do
            for bin in ${DISCHARGE_BIN:-./build-gpu/bench/discharge}; do
                echo "{\"binary\": \"$bin\", \"round\": $round}" >>"$OUT/discharge.log"
                timeout 200 "$bin" cuda 40 0.5 0.05 >>"$OUT/discharge.log" 2>&1
                echo "discharge $bin round $round: rc $?"
            done
        done
        grep -E '^\{' "$OUT/discharge.log" | cut -c1-300
        ;;
    smallab)
        # SMALL-SYSTEMS, each setting twice, alternating, in one command.
        # SMALL_SETTINGS: one setting a word, its variables joined by commas; BIN=path picks the
        # benchmark binary (a baseline's: `baseline` builds one), the rest are put in the environment
        # (e.g. DEME_CUDA_OVERLAP_LAUNCHES=0, DEME_CUDA_OWNER_THREADS=128, DEME_BENCH_FORCE_THREADS=128).
        # SMALL_MODES: the detection modes (default async; "sync async" runs both).
        for round in 1 2; do
            for c in drum impact; do
                for mode in ${SMALL_MODES:-async}; do
                for setting in ${SMALL_SETTINGS:-BIN=./build-gpu/bench/small_systems}; do
                    bin=./build-gpu/bench/small_systems
                    vars=()
                    for kv in ${setting//,/ }; do
                        case "$kv" in
                        BIN=*) bin="${kv#BIN=}" ;;
                        *) vars+=("$kv") ;;
                        esac
                    done
                    echo "{\"setting\": \"$setting\", \"mode\": \"$mode\", \"round\": $round}" >>"$OUT/smallab.log"
                    # SMALL_DRUM_STEPS: the drum's timed steps (its default 20,000 take about 0.6 s, and
                    # its runs spread by several per cent).
                    steps=""
                    [ "$c" = drum ] && steps="${SMALL_DRUM_STEPS:-}"
                    env "${vars[@]}" DEME_BENCH_TIMING=1 timeout 200 "$bin" $c "" "$steps" cuda "$mode" >>"$OUT/smallab.log" 2>&1
                    echo "smallab $c $mode $setting round $round: rc $?"
                done
                done
            done
        done
        grep -E "^\{" "$OUT/smallab.log" | cut -c1-330
        ;;
    sweep)
        # Many small runs on one GPU at once (a calibration sweep): 1, 2, 4 and 8 drum solvers, each
        # on its own thread, timed together (5,000 warm-up and 20,000 timed steps each).
        for n in ${SWEEP:-1 2 4 8}; do
            timeout 300 ./build-gpu/bench/small_systems drum 5000 20000 cuda async "$n" >>"$OUT/sweep.jsonl" 2>&1
            echo "sweep $n solvers: rc $? $(tail -n 1 "$OUT/sweep.jsonl" | grep -o '"total_steps_per_s": [0-9.e+]*')"
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
    mixerab)
        # MIXER-BENCH early, spheres at r = 2.5 mm (2.9 M), 2,000 warm-up and 2,000 timed steps, each
        # binary of MIXERS (a baseline's and this build's) twice, alternating, in one command.
        for round in 1 2; do
            for bin in ${MIXERS:-./build-gpu/bench/mixer}; do
                echo "{\"binary\": \"$bin\", \"round\": $round}" >>"$OUT/mixerab.jsonl"
                timeout 200 "$bin" .benchdata/internal_mixer.obj 0.0025 spheres 2000 2000 2>&1 | tee -a "$OUT/mixerab.jsonl" | tail -n 1 | cut -c1-300
            done
        done
        ;;
    earlyab)
        # The early mixer at r = 1 mm (45.8 M spheres, 60 steps, synchronous), alternating over
        # MIXERS (default the baseline's and this build's: `baseline` builds the first; BASE=<dir>
        # `baseline` builds another tree beside it) for EARLY_ROUNDS rounds (default 2): each run's
        # JSON line, memory table and phases in $OUT/early.log, and a line per run here (binary,
        # sphere-steps/s, device B/sphere, host peak MiB).
        for round in $(seq "${EARLY_ROUNDS:-2}"); do
            for bin in ${MIXERS:-.base/build-gpu/bench/mixer ./build-gpu/bench/mixer}; do
                echo "== $bin round $round" >>"$OUT/early.log"
                DEME_BENCH_TIMING=1 timeout 120 "$bin" .benchdata/internal_mixer.obj 0.001 spheres 0 60 5e-7 1 sync \
                    >>"$OUT/early.log" 2>&1
                tail -n 40 "$OUT/early.log" | grep '"case"' | tail -n 1 |
                    sed -E 's/.*"sphere_steps_per_s": ([^,]*).*"device_bytes_per_sphere": ([^,]*).*"peak_host_mem_mib": ([^,]*).*/'"${bin//\//\\/}"' \1 \2 \3/'
            done
        done
        ;;
    settled)
        # The settled variant: 0.25 s of mixing as 125000 warm-up steps of 2e-6 s (the grains land on
        # the floor), then 2000 timed steps of 5e-7 s. SETTLED="r:kind[:mode] ..." picks the cases
        # (mode auto, sync or async; auto by default); MIXERS lists the benchmark binaries, each run
        # on every case in turn (a baseline's and this build's: same machine, same command).
        for spec in ${SETTLED:-0.004:spheres 0.004:clumps}; do
            IFS=: read -r r kind mode <<<"$spec"
            for bin in ${MIXERS:-./build-gpu/bench/mixer}; do
                echo "{\"binary\": \"$bin\"}" >>"$OUT/settled.jsonl"
                timeout "${SETTLED_TIMEOUT:-550}" "$bin" .benchdata/internal_mixer.obj "$r" "$kind" 125000 2000 2e-6 1 "${mode:-auto}" 2>&1 |
                    tee -a "$OUT/settled.jsonl" | tail -n 2
            done
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
    profile-small)
        # Nsight Compute: every kernel of some drum and impact steps (launched one by one,
        # DEME_CUDA_GRAPHS=0, synchronous detection, so a detection's kernels are among them), after
        # the warm-up: durations, DRAM traffic, grid and register counts.
        for c in drum impact; do
            DEME_CUDA_GRAPHS=0 DEME_CUDA_PROFILE_FROM_STEP=20001 timeout 300 ncu --profile-from-start off --clock-control none \
                --launch-count 90 --csv \
                --metrics gpu__time_duration.sum,dram__bytes_read.sum,dram__bytes_write.sum,launch__grid_size,launch__block_size,launch__registers_per_thread,sm__warps_active.avg.pct_of_peak_sustained_active \
                ./build-gpu/bench/small_systems $c 20000 300 cuda sync >"$OUT/ncu-$c.csv" 2>"$OUT/ncu-$c.err"
            echo "profile-small $c: rc $? ($(wc -l <"$OUT/ncu-$c.csv") lines)"
        done
        ;;
    profile-step)
        # Where a drum step's time goes: Nsight Compute's full sections (stall reasons, spills,
        # occupancy) for some force passes and fused owner steps after the warm-up, kernels launched
        # one by one (PROFILE_CASE=impact the impact, PROFILE_LAUNCHES how many; PROFILE_WARM and
        # PROFILE_STEPS the benchmark's warm-up and timed steps, PROFILE_FROM the first step profiled:
        # the impact's ball is released after its warm-up and reaches the bed about 2,000 steps on).
        warm=${PROFILE_WARM:-20000}
        DEME_CUDA_GRAPHS=0 DEME_CUDA_PROFILE_FROM_STEP=${PROFILE_FROM:-$((warm + 1))} timeout 300 ncu --profile-from-start off --clock-control none \
            -k regex:'deme_force_pass|deme_integrate' --launch-count ${PROFILE_LAUNCHES:-4} --set full --import-source no \
            ./build-gpu/bench/small_systems ${PROFILE_CASE:-drum} "$warm" ${PROFILE_STEPS:-300} cuda sync >"$OUT/ncu-step.txt" 2>"$OUT/ncu-step.err"
        echo "profile-step ncu: rc $? ($(wc -l <"$OUT/ncu-step.txt") lines)"
        ;;
    profile-sass)
        # One kernel of a drum step instruction by instruction (PROFILE_KERNEL, default the fused owner
        # step): Nsight Compute's source page as SASS with each instruction's executions and warp
        # stall samples (where a lab-scale step's serial path spends its time), after the warm-up.
        DEME_CUDA_GRAPHS=0 DEME_CUDA_PROFILE_FROM_STEP=20001 timeout 300 ncu --profile-from-start off --clock-control none \
            -k regex:"${PROFILE_KERNEL:-deme_integrate_and_place}" --launch-count 1 --set full --import-source no \
            --page source --print-source sass --csv \
            ./build-gpu/bench/small_systems ${PROFILE_CASE:-drum} 20000 300 cuda sync >"$OUT/ncu-sass.csv" 2>"$OUT/ncu-sass.err"
        echo "profile-sass ncu: rc $? ($(wc -l <"$OUT/ncu-sass.csv") lines)"
        ;;
    compile)
        # A custom force model's Initialize cost on the GPU backend (NVRTC plus the host build).
        ./build-gpu/bench/model_compile - cuda 2>&1 | tee -a "$OUT/compile.jsonl" | tail -n 3
        ;;
    output)
        # The output tests on the GPU backend: VTU files read back by meshio against the CSV, the
        # .pvd series, failed writes, snapshots read by PIL; the writers read the state the device
        # has moved on to (downloaded on demand). Needs Debian's python3-meshio and python3-pil.
        "$PY" -c "import meshio, PIL" 2>/dev/null ||
            echo "output: $PY lacks meshio or PIL (apt-get install python3-meshio python3-pil, or tests/gpu/python-deps.sh): the read-back tests will fail"
        DEME_TEST_PYTHON="$PY" DEME_BACKEND=cuda ./build-gpu/tests/deme_tests --gtest_filter='VtuOutput*:OutputFailure*:Snapshot*:Output.*:ProgressReport.Callback*' \
            >"$OUT/output.log" 2>&1
        echo "output (DEME_BACKEND=cuda): rc $? ($(grep -c '^\[       OK' "$OUT/output.log") ok)"
        grep -E '^\[  FAILED|^\[  SKIPPED' "$OUT/output.log" | head -20
        timeout 300 ./build-gpu/bench/output_write solver 1000000 /tmp 2>&1 | tee -a "$OUT/output.jsonl" | tail -n 2
        ;;
    validation)
        # The validation suite (validation/run.py) in full on the GPU, with the module and demos of
        # build-gpu; VALIDATION_CASES names some cases (default: all), VALIDATION_ARGS adds options
        # (e.g. --quick). Plots and verdicts go to $OUT/validation.
        DEME_BUILD_DIR="$PWD/build-gpu" PYTHONPATH="$PWD/build-gpu/python" DEME_CACHE_DIR="$DEME_CACHE_DIR" \
            "$PY" validation/run.py --backend cuda --out "$OUT/validation" ${VALIDATION_ARGS:-} ${VALIDATION_CASES:-} \
            >"$OUT/validation.log" 2>&1
        echo "validation (cuda): rc $?"
        tail -n 40 "$OUT/validation.log"
        ;;
    filter)
        # The gtest filter in FILTER, with DEME_BACKEND=cuda for the tests that are not backend tests
        # (a backend test's instance sets its own: FILTER='SettledBed.*/cuda' takes the GPU's).
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
