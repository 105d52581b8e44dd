"""Loads the native module of the precision chosen by SUPERDEX_PRECISION (float by default).

SUPERDEX_NATIVE_DIR=DIR loads it from DIR instead of the installed package: `tools/dev.sh
sanitize` points it at the AddressSanitizer build (build/asan/python) to run the Python tests on
sanitized modules.
"""

import glob
import importlib
import importlib.util
import os
import sys

_VALUES = {"": "float", "float": "float", "float32": "float", "single": "float", "double": "double", "float64": "double"}

_requested = os.environ.get("SUPERDEX_PRECISION", "").strip().lower()
if _requested not in _VALUES:
    raise ImportError(
        f"SUPERDEX_PRECISION={os.environ['SUPERDEX_PRECISION']!r} is not understood: use 'float' (default) or 'double'"
    )
PRECISION = _VALUES[_requested]
# The sparse Cholesky behind soft bodies opens small OpenMP regions. The engine keeps them on the
# thread that opens them (sparse_cholesky.cpp); should it not find the OpenMP runtime to tell,
# their threads would spin between regions, taking a core from the engine's own worker threads
# and from scenes stepped on other threads. Waiting threads sleep instead unless the user chose
# otherwise (read when the OpenMP runtime loads, with the module below).
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def _load_from(directory: str, name: str):
    """Imports the extension module `superdex.<name>` from the file `<directory>/<name>.*.so`."""
    files = sorted(glob.glob(os.path.join(directory, f"{name}.*.so")))
    if not files:
        raise ImportError(f"SUPERDEX_NATIVE_DIR={directory!r} holds no {name}.*.so")
    spec = importlib.util.spec_from_file_location(f"superdex.{name}", files[0])
    loaded = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = loaded
    spec.loader.exec_module(loaded)
    return loaded


_native_dir = os.environ.get("SUPERDEX_NATIVE_DIR", "").strip()
if _native_dir:
    module = _load_from(_native_dir, f"_superdex_{PRECISION}")
else:
    module = importlib.import_module(f"superdex._superdex_{PRECISION}")
