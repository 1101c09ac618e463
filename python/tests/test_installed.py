"""The installed package, not the build tree: `cmake --install` into a temporary prefix, then a
fresh interpreter that sees only that prefix imports deme and DEME, finds its data files inside
the installed package, and runs a small simulation with them."""
import ast
import os
import subprocess
import sys

import pytest

import deme

BUILD = os.environ.get("DEME_TEST_BUILD_DIR")
CMAKE = os.environ.get("DEME_TEST_CMAKE", "cmake")
PYDIR = os.environ.get("DEME_TEST_PYTHON_INSTALL_DIR")

CHECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "installed_check.py")


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    if not BUILD or not PYDIR:
        pytest.skip("run by ctest, which passes the build folder")
    prefix = tmp_path_factory.mktemp("prefix")
    res = subprocess.run([CMAKE, "--install", BUILD, "--prefix", str(prefix)], capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr
    return prefix


def site_dir(prefix):
    return PYDIR if os.path.isabs(PYDIR) else os.path.join(str(prefix), PYDIR)


def test_installed_package_imports_and_finds_its_data(prefix, tmp_path):
    site = site_dir(prefix)
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "DEME_"))}
    env["PYTHONPATH"] = site
    env["PYTHONNOUSERSITE"] = "1"
    res = subprocess.run([sys.executable, CHECK], cwd=tmp_path, env=env, capture_output=True, text=True,
                         timeout=120)
    assert res.returncode == 0, res.stdout + res.stderr
    lines = dict(l.split(" ", 1) for l in res.stdout.splitlines())
    pkg = os.path.join(site, "deme")
    assert lines["module"] == os.path.join(pkg, "__init__.py")
    assert lines["mesh"] == os.path.join(pkg, "data", "mesh", "internal_mixer.obj")
    assert lines["clump"] == os.path.join(pkg, "data", "clumps", "3_clump.csv")
    assert float(lines["z"]) < 0.3  # it fell


def test_installed_package_has_stubs_and_marker(prefix):
    pkg = os.path.join(site_dir(prefix), "deme")
    for name in ("py.typed", "__init__.pyi", "_deme.pyi", "__init__.py", os.path.join("..", "DEME.py")):
        assert os.path.isfile(os.path.join(pkg, name)), name
    assert any(n.startswith("_deme") and n.endswith(".so") for n in os.listdir(pkg))


def test_cpp_install_has_the_data_files(prefix):
    for rel in ("mesh/internal_mixer.obj", "clumps/3_clump.csv"):
        assert os.path.isfile(os.path.join(str(prefix), "share", "deme", "data", rel)), rel


def test_stubs_cover_the_module():
    # The stubs of the package under test name every public class, function and method.
    pkg = os.path.dirname(deme.__file__)
    tree = ast.parse(open(os.path.join(pkg, "_deme.pyi")).read())
    stubbed = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            stubbed[node.name] = {n.name for n in node.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
        elif isinstance(node, ast.FunctionDef):
            stubbed[node.name] = set()
    import deme._deme as ext

    for name in dir(ext):
        obj = getattr(ext, name)
        if name.startswith("_") or not callable(obj) or isinstance(obj, type) and issubclass(obj, BaseException):
            continue
        assert name in stubbed, name
        if isinstance(obj, type) and not hasattr(obj, "__members__"):
            methods = {m for m, f in vars(obj).items() if not m.startswith("_") and callable(f)}
            assert methods <= stubbed[name], (name, methods - stubbed[name])
