"""Robot description files shipped by other Python packages. This module does not load the
native engine, so processes that only run other simulators (the benchmarks' peers) can use it."""

from __future__ import annotations

import importlib.metadata
from pathlib import Path

PANDA_URDF = "robots/panda_description/urdf/panda.urdf"


def example_robot_data_file(relative: str = PANDA_URDF) -> Path:
    """The absolute path of `relative` (for example PANDA_URDF) inside the installed
    example-robot-data package. Raises FileNotFoundError naming the file and the package
    version when the package does not ship it."""
    dist = importlib.metadata.distribution("example-robot-data")
    for f in dist.files or []:
        if str(f).replace("\\", "/").endswith(relative):
            return Path(dist.locate_file(f)).resolve()
    raise FileNotFoundError(f"{relative} is not part of example-robot-data {dist.version}")


def example_robot_data_urdfs() -> list[Path]:
    """Every URDF the installed example-robot-data package ships, sorted by path. Raises
    FileNotFoundError naming the package version when it ships none."""
    dist = importlib.metadata.distribution("example-robot-data")
    files = sorted(Path(dist.locate_file(f)).resolve() for f in dist.files or [] if str(f).endswith(".urdf"))
    if not files:
        raise FileNotFoundError(f"example-robot-data {dist.version} ships no URDF")
    return files
