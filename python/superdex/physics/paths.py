"""Locations of the bundled assets."""

import os
from pathlib import Path

from superdex._native import module as _m

_REPO_ASSETS = Path(__file__).resolve().parents[3] / "assets"


def get_assets_root() -> Path:
    """The assets folder: $SUPERDEX_ASSETS_PATH if set, else the repository's `assets/`."""
    override = os.environ.get("SUPERDEX_ASSETS_PATH")
    root = Path(override) if override else _REPO_ASSETS
    if not root.is_dir():
        raise _m.Error(f"assets folder {str(root)!r} does not exist (set SUPERDEX_ASSETS_PATH to the assets folder)")
    return root


def resolve_asset(relative) -> Path:
    """Absolute path of an asset given relative to the assets folder; raises Error if missing."""
    rel = Path(relative)
    if rel.is_absolute() or ".." in rel.parts:
        raise _m.Error(f"resolve_asset: {str(relative)!r} must be a relative path inside the assets folder")
    path = get_assets_root() / rel
    if not path.exists():
        raise _m.Error(f"resolve_asset: {str(relative)!r} not found under {str(get_assets_root())!r}")
    return path
