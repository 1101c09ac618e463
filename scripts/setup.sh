#!/usr/bin/env bash
# Installs what the build and the tests need (Debian packages) if it is missing, then configures and
# builds the engine, its Python module, tests, demos and benchmarks in ./build (Release).
# The Python module is built for Debian's /usr/bin/python3 (the python3 first on PATH may be
# another interpreter, without Debian's packages): PYTHONPATH=build/python imports it from the
# build tree.
set -euo pipefail
cd "$(dirname "$0")/.."

need=()
command -v cmake >/dev/null || need+=(cmake)
command -v g++ >/dev/null || need+=(g++)
[ -f /usr/include/gtest/gtest.h ] || need+=(libgtest-dev)
# The Python module and its tests: headers, pybind11, numpy, pytest; pip, venv, setuptools and
# wheel for the pip route (`pip install --no-build-isolation .`, tested by ctest python.pip_install).
[ -x /usr/bin/python3 ] || need+=(python3)
py_has() { [ -x /usr/bin/python3 ] && /usr/bin/python3 -c "import $1" >/dev/null 2>&1; }
py_include="$( [ -x /usr/bin/python3 ] && /usr/bin/python3 -c 'import sysconfig; print(sysconfig.get_path("include"))' 2>/dev/null || true)"
[ -n "$py_include" ] && [ -f "$py_include/Python.h" ] || need+=(python3-dev)
[ -f /usr/lib/cmake/pybind11/pybind11Config.cmake ] || [ -f /usr/share/cmake/pybind11/pybind11Config.cmake ] ||
    need+=(pybind11-dev)
py_has numpy || need+=(python3-numpy)
py_has pytest || need+=(python3-pytest)
py_has pip || need+=(python3-pip)
# (Debian's interpreter imports ensurepip without python3-venv, but cannot make a venv with pip)
dpkg-query -W -f='${Status}' python3-venv 2>/dev/null | grep -q "ok installed" || need+=(python3-venv)
py_has setuptools || need+=(python3-setuptools)
py_has wheel || need+=(python3-wheel)
[ -f /usr/include/zlib.h ] || need+=(zlib1g-dev)  # PNG snapshots, compressed VTU
# The tests read output back with readers the engine has no part in: meshio (VTU) and PIL (PNG),
# for Debian's own /usr/bin/python3.
/usr/bin/python3 -c "import meshio" 2>/dev/null || need+=(python3-meshio)
/usr/bin/python3 -c "import PIL" 2>/dev/null || need+=(python3-pil)
# The validation suite (validation/run.py) draws its plots with matplotlib.
/usr/bin/python3 -c "import matplotlib" 2>/dev/null || need+=(python3-matplotlib)
# ... and runs LIGGGHTS 3.8 beside the engine (validation/cases/peer_hopper.py).
command -v liggghts >/dev/null || need+=(liggghts)
if [ ${#need[@]} -gt 0 ]; then
    echo "installing: ${need[*]}"
    SUDO=""
    [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
