"""Shared set-up of the Python tests. ctest runs each test file with /usr/bin/python3 -m pytest and
PYTHONPATH=<build>/python (python/tests/PythonTests.cmake); DEME_BACKEND picks the backend as for
the C++ tests (tests/gpu/run.sh runs this suite with DEME_BACKEND=cuda)."""
import math
import os

import numpy as np
import pytest

import deme


def sphere_mass(r, density):
    return density * 4.0 / 3.0 * math.pi * r ** 3


def material(sim, E=1e8, nu=0.3, CoR=0.5, mu=0.5, Crr=0.0, **extra):
    props = {"E": E, "nu": nu, "CoR": CoR, "mu": mu, "Crr": Crr}
    props.update(extra)
    return sim.LoadMaterial(props)


def quiet_solver():
    sim = deme.DEMSolver()
    sim.SetVerbosity("QUIET")
    return sim


def package_env(extra=None):
    """The environment a subprocess needs to import the same package as this test."""
    env = dict(os.environ)
    env.update(extra or {})
    return env


@pytest.fixture
def sim():
    return quiet_solver()


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
