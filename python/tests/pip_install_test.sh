#!/usr/bin/env bash
# ctest python_pip_install: the README's pip route, offline, into a fresh virtual environment that
# sees Debian's packages (numpy, setuptools, wheel):
#   python3 -m venv --system-site-packages .venv && .venv/bin/pip install --no-build-isolation .
# on a copy of the source tree (pip builds in the tree it is given), then installed_check.py from
# outside both trees. The build is CPU-only (-DDEME_ENABLE_CUDA=OFF) and setup.py leaves out the
# tests, demos and benchmarks: the library and the module alone, to keep this test at a couple of
# minutes on 2 cores (the CUDA backend's nvcc objects would triple that, and the module's CUDA
# build is the same code: tests/gpu/run.sh builds and tests it).
#   pip_install_test.sh <source dir> <scratch dir> <python>
set -euo pipefail
src="$1" work="$2" python="$3"
rm -rf "$work"
mkdir -p "$work/src"
tar -C "$src" --exclude='./build*' --exclude='./.git' --exclude='./gpu-test-out' --exclude='./DemoOutput*' \
    --exclude='./.benchdata' --exclude='*.egg-info' --exclude='__pycache__' -cf - . | tar -C "$work/src" -xf -
"$python" -m venv --system-site-packages "$work/venv"
CMAKE_ARGS="-DDEME_ENABLE_CUDA=OFF" CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-2}" \
    "$work/venv/bin/pip" install --no-build-isolation --no-index --quiet "$work/src"
site="$("$work/venv/bin/python" -c 'import sysconfig; print(sysconfig.get_path("platlib"))')"
mkdir -p "$work/run"
cd "$work/run"
out="$(env -u PYTHONPATH PYTHONNOUSERSITE=1 "$work/venv/bin/python" "$src/python/tests/installed_check.py")"
echo "$out"
# The module and its data files come from the environment's site-packages, nowhere else.
grep -qx "module $site/deme/__init__.py" <<<"$out"
grep -qx "mesh $site/deme/data/mesh/internal_mixer.obj" <<<"$out"
grep -qx "clump $site/deme/data/clumps/3_clump.csv" <<<"$out"
[ -f "$site/deme/_deme.pyi" ] && [ -f "$site/deme/py.typed" ] && [ -f "$site/DEME.py" ]
shown="$("$work/venv/bin/pip" show deme)"
grep -q '^Version: ' <<<"$shown"
echo "pip install: ok"
