#!/usr/bin/env bash
# Fetches, on the development machine (Debian 12), the Debian packages the `python` step of
# tests/gpu/run.sh needs, into .pydebs/ (ignored; name it in the device run's carry): Python 3.11 with
# its headers, numpy, pybind11 and pytest. A GPU machine whose own Python lacks numpy or pybind11
# (the nvidia-h200 machines: Ubuntu, Python 3.12, no network) then unpacks them into a prefix of its
# own (never into /) and builds and tests the module with that interpreter.
set -euo pipefail
cd "$(dirname "$0")/../.."
grep -qx '/.pydebs/' .git/info/exclude 2>/dev/null || echo '/.pydebs/' >>.git/info/exclude
mkdir -p .pydebs
cd .pydebs
apt-get download python3.11 python3.11-minimal libpython3.11-minimal libpython3.11-stdlib libpython3.11 \
    libpython3.11-dev python3.11-dev python3-numpy pybind11-dev python3-pytest python3-pluggy python3-iniconfig \
    python3-packaging python3-attr python3-py libblas3 liblapack3 libgfortran5
du -sh .
