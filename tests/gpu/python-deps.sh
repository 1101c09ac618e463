#!/usr/bin/env bash
# Fetches, on the development machine (Debian 12), the Debian packages the `python` step of
# tests/gpu/run.sh needs, into .pydebs/ (ignored; name it in the device run's carry): Python 3.11 with
# its headers, numpy, pybind11 and pytest, meshio and PIL for the output step, and matplotlib for the
# validation suite. A GPU machine whose own Python lacks numpy or pybind11
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
# The output step's readers (meshio for VTU, PIL for PNG) with what they load.
apt-get download python3-meshio python3-pil python3-rich python3-lxml python3-importlib-metadata python3-pygments \
    python3-markdown-it python3-mdurl python3-zipp libjpeg62-turbo liblcms2-2 libopenjp2-7 libtiff6 libwebp7 \
    libwebpdemux2 libwebpmux3 libimagequant0 libraqm0 libfreetype6 libxslt1.1 libxml2 libdeflate0 libjbig0 liblerc4 \
    libfribidi0 libharfbuzz0b libgraphite2-3 libbrotli1 libpng16-16 libicu72 libglib2.0-0
# matplotlib, for the validation suite's plots (validation/run.py).
apt-get download python3-matplotlib python-matplotlib-data python3-dateutil python3-pyparsing python3-six \
    python3-contourpy python3-cycler python3-fonttools python3-kiwisolver libqhull-r8.0 fonts-dejavu-core fonts-lyx
du -sh .
