"""Builds the Python module with CMake for pip: `pip install --no-build-isolation .` (offline; the
build needs cmake, a C++17 compiler, pybind11-dev and python3-numpy; docs/python.md).

The extension deme._deme is the CMake target _deme (python/CMakeLists.txt), configured without
tests, demos and benchmarks in build-pip/cmake; its package files (type stubs, py.typed, the data
folder) are copied beside it into the wheel. CMAKE_ARGS adds CMake options (for instance
CMAKE_ARGS="-DDEME_ENABLE_CUDA=OFF" for a CPU-only build); CMAKE_BUILD_PARALLEL_LEVEL sets the
build's parallel jobs.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(DEME VERSION ([0-9.]+)", f.read()).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = os.path.join(ROOT, "build-pip", "cmake")
        configure = ["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                     "-DDEME_BUILD_TESTS=OFF", "-DDEME_BUILD_DEMOS=OFF", "-DDEME_BUILD_BENCH=OFF",
                     "-DDEME_PYTHON_REQUIRED=ON", "-DPython3_EXECUTABLE=" + sys.executable]
        configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        subprocess.check_call(configure)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.check_call(["cmake", "--build", build_dir, "--target", "_deme", "-j", jobs])

        built_pkg = os.path.join(build_dir, "python", "deme")
        target = self.get_ext_fullpath(ext.name)
        target_dir = os.path.dirname(target)
        os.makedirs(target_dir, exist_ok=True)
        (so,) = [f for f in os.listdir(built_pkg) if f.startswith("_deme") and f.endswith(".so")]
        shutil.copyfile(os.path.join(built_pkg, so), target)
        for name in ("_deme.pyi", "__init__.pyi", "py.typed"):
            shutil.copyfile(os.path.join(built_pkg, name), os.path.join(target_dir, name))
        data = os.path.join(target_dir, "data")
        shutil.rmtree(data, ignore_errors=True)
        for sub in ("mesh", "clumps"):
            shutil.copytree(os.path.join(ROOT, "data", sub), os.path.join(data, sub))


setup(
    version=project_version(),
    packages=["deme"],
    package_dir={"": "python"},
    py_modules=["DEME"],
    ext_modules=[CMakeExtension("deme._deme")],
    cmdclass={"build_ext": CMakeBuild},
    # Kept apart from CMake's own build/ folder of the README's commands.
    options={"build": {"build_base": os.path.join("build-pip", "setuptools")}},
    zip_safe=False,
)
