"""Loads the native module of the precision chosen by SUPERDEX_PRECISION (float by default)."""

import importlib
import os

_VALUES = {"": "float", "float": "float", "float32": "float", "single": "float", "double": "double", "float64": "double"}

_requested = os.environ.get("SUPERDEX_PRECISION", "").strip().lower()
if _requested not in _VALUES:
    raise ImportError(
        f"SUPERDEX_PRECISION={os.environ['SUPERDEX_PRECISION']!r} is not understood: use 'float' (default) or 'double'"
    )
PRECISION = _VALUES[_requested]
# The sparse Cholesky behind soft bodies opens small OpenMP regions; by default their threads then
# spin, taking a core from the engine's own worker threads and from scenes stepped on other
# threads. Waiting threads sleep instead unless the user chose otherwise (read when the OpenMP
# runtime loads, with the module below).
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
module = importlib.import_module(f"superdex._superdex_{PRECISION}")
