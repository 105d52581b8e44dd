"""superdex.physics: the engine's Python API (see API.md).

The float32 build is loaded by default; SUPERDEX_PRECISION=double selects the float64 build.
"""

from superdex._native import module as _m

# every public name of the native module but its submodules: robotics (superdex.robotics) and
# model (superdex.physics.model, a Python module over it)
for _name in dir(_m):
    if not _name.startswith("_") and _name not in ("robotics", "model"):
        globals()[_name] = getattr(_m, _name)
del _name
# the native submodules import as superdex.physics.<name> too
import sys as _sys  # noqa: E402

for _sub in ("experimental", "prefab"):
    _sys.modules[f"{__name__}.{_sub}"] = getattr(_m, _sub)

from superdex.physics import debugger, model, paths  # noqa: E402  (submodules, after the native names)

__all__ = [name for name in dir() if not name.startswith("_")]
