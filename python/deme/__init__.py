"""DEME: a Discrete Element Method engine for granular materials.

The classes and functions are the C++ API's (namespace deme), with the same names and argument
order: DEMSolver, DEMClumpTemplate, DEMClumpBatch, DEMExternObj, DEMMeshConnected, DEMTracker,
DEMInspector, DEMForceModel, HCPSampler, GridSampler, GetDEMEDataFile. `import DEME` gives this
same module (the paper's name). docs/python.md describes the conversions:

  Float3           a list, tuple or numpy array of 3 numbers (returned as float32 arrays of 3)
  Quaternion       4 numbers in the C++ float4 order x, y, z, w (w the scalar part; identity
                   [0, 0, 0, 1])
  Float3Array      an (N, 3) array or nested lists (returned as float32 (N, 3), C order)
  QuaternionArray  an (N, 4) array, columns x, y, z, w
  FloatArray       a 1-D array of numbers (returned as float32 (N,))
  Int3Array        an (N, 3) array of integers (mesh faces; returned as int32)

Errors from the engine are deme.Error (a RuntimeError); arguments of the wrong type raise
TypeError naming the call.
"""
from typing import Sequence, Union

import numpy as _np

from ._deme import *  # noqa: F401,F403  (the compiled API)
from ._deme import Error, GetDEMEDataFile, GetDEMEDataDirs, __version__  # noqa: F401

Error.__module__ = "deme"  # tracebacks say deme.Error, the name to catch

# The names used in the signatures help() shows (see the module docstring).
Float3 = Union[Sequence[float], _np.ndarray]
Quaternion = Union[Sequence[float], _np.ndarray]
Float3Array = Union[Sequence[Sequence[float]], _np.ndarray]
QuaternionArray = Union[Sequence[Sequence[float]], _np.ndarray]
FloatArray = Union[Sequence[float], _np.ndarray]
Int3Array = Union[Sequence[Sequence[int]], _np.ndarray]
