#!/usr/bin/env bash
# Installs what the build and the tests need (Debian packages) if it is missing, then configures and
# builds the engine, its tests, demos and benchmarks in ./build (Release).
set -euo pipefail
cd "$(dirname "$0")/.."

need=()
command -v cmake >/dev/null || need+=(cmake)
command -v g++ >/dev/null || need+=(g++)
[ -f /usr/include/gtest/gtest.h ] || need+=(libgtest-dev)
[ -f /usr/include/zlib.h ] || need+=(zlib1g-dev)  # PNG snapshots, compressed VTU
# The tests read output back with readers the engine has no part in: meshio (VTU) and PIL (PNG),
# for Debian's own /usr/bin/python3.
/usr/bin/python3 -c "import meshio" 2>/dev/null || need+=(python3-meshio)
/usr/bin/python3 -c "import PIL" 2>/dev/null || need+=(python3-pil)
if [ ${#need[@]} -gt 0 ]; then
    echo "installing: ${need[*]}"
    SUDO=""
    [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
