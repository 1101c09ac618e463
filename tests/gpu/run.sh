#!/usr/bin/env bash
# GPU test run (on a machine with an NVIDIA GPU; see docs/gpu-tests.md): builds with the CUDA backend,
# runs the CUDA unit tests, the whole suite with DEME_BACKEND=cuda, and the CPU/GPU parity tests.
# Logs go to $OUT (default ./gpu-test-out).
#   tests/gpu/run.sh [build|unit|suite|bench ...]   (default: build unit suite)
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
        DEME_BACKEND=cuda ctest --test-dir build-gpu -j4 -E 'tsan|package' --timeout 300 >"$OUT/suite.log" 2>&1
        echo "suite (DEME_BACKEND=cuda): rc $?"
        grep -E 'tests passed|\(Failed\)|\(Timeout\)|\(SEGFAULT\)|Exception' "$OUT/suite.log" | head -40
        ;;
    bench)
        obj=.benchdata/internal_mixer.obj
        for r in 0.004 0.0025 0.0015; do
            for kind in spheres clumps; do
                timeout 300 ./build-gpu/bench/mixer "$obj" "$r" "$kind" 2000 2000 2>&1 | tee -a "$OUT/bench.jsonl" | tail -n 3
            done
        done
        ;;
    *)
        echo "unknown step $step" >&2
        exit 2
        ;;
    esac
done
