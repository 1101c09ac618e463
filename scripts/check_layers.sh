#!/usr/bin/env bash
# Checks that no source file under src/ includes a header of a higher layer (docs/ARCHITECTURE.md):
#   0 physics            single-source math (DEME_HD)
#   1 state parallel jit the state described once; OpenMP thread helpers; run-time compilation
#   2 kinematics dynamics codegen forcemodel
#                        per-item rules of detection, history and the step; code generation
#   3 runtime            the one step loop and schedule, and the backend interface it drives
#   4 backend            backend/cpu and backend/cuda: the interface's implementations
#   5 io                 readers and writers
#   6 api                the DEMSolver facade
# An include of the same layer or a lower one is fine; one that goes up fails the script, naming
# the file, the line and both layers. The public headers (include/deme) are below everything.
set -euo pipefail
cd "$(dirname "$0")/.."

layer_of() {
    case "$1" in
        physics/*) echo 0 ;;
        state/* | parallel/* | jit/*) echo 1 ;;
        kinematics/* | dynamics/* | codegen/* | forcemodel/*) echo 2 ;;
        runtime/*) echo 3 ;;
        backend/*) echo 4 ;;
        io/*) echo 5 ;;
        api/*) echo 6 ;;
        *) echo "" ;;
    esac
}

status=0
count=0
while IFS= read -r -d '' file; do
    rel="${file#src/}"
    from=$(layer_of "$rel")
    if [ -z "$from" ]; then
        echo "check_layers: $file is in no layer (add its folder to scripts/check_layers.sh)"
        status=1
        continue
    fi
    while IFS=: read -r line target; do
        to=$(layer_of "$target")
        [ -z "$to" ] && continue  # a system header or a public one
        count=$((count + 1))
        if [ "$to" -gt "$from" ]; then
            echo "check_layers: $file:$line includes \"$target\": layer $to (${target%%/*}) is above layer $from (${rel%%/*})"
            status=1
        fi
    done < <(grep -n -E '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$file" |
        sed -E 's/^([0-9]+):[[:space:]]*#[[:space:]]*include[[:space:]]*"([^"]+)".*/\1:\2/')
done < <(find src -type f \( -name '*.h' -o -name '*.cpp' -o -name '*.cu' -o -name '*.cuh' -o -name '*.inl' \) -print0)

if [ "$status" -eq 0 ]; then
    echo "check_layers: $count includes between layers, none goes up"
fi
exit "$status"
