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


def pouring_block(sync=None):
    """A block of 2.5 mm spheres (HCP) in an open-topped 0.1 m box, under gravity, not yet initialized;
    sync True/False picks the contact detection mode."""
    r = 0.0025
    sim = quiet_solver()
    mat = material(sim, E=1e7, CoR=0.3, mu=0.5)
    sim.InstructBoxDomainDimension(0.1, 0.1, 0.1)
    sim.InstructBoxDomainBoundingBC("top_open", mat)
    pts = deme.HCPSampler(2.05 * r).SampleBox([0, 0, -0.0385], [0.02, 0.02, 0.008])
    sim.AddClumps(sim.LoadSphereType(sphere_mass(r, 2600), r, mat), pts)
    sim.SetInitTimeStep(2e-5)
    sim.SetGravitationalAcceleration([0, 0, -9.81])
    if sync is not None:
        sim.SetSynchronousContactDetection(sync)
    return sim, len(pts)


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
