"""Locations of the bundled assets: the assets folder ($SUPERDEX_ASSETS_PATH, else the
repository's `assets/`), and asset paths resolved against it."""

import os
from pathlib import Path

from superdex._native import module as _m

_REPO_ASSETS = Path(__file__).resolve().parents[3] / "assets"

__all__ = ["get_assets_root", "resolve_asset", "resolve_asset_root"]


def get_assets_root() -> Path:
    """The assets folder: $SUPERDEX_ASSETS_PATH if set, else the repository's `assets/`."""
    override = os.environ.get("SUPERDEX_ASSETS_PATH")
    root = Path(override).expanduser() if override else _REPO_ASSETS
    if not root.is_dir():
        raise _m.Error(f"assets folder {str(root)!r} does not exist (set SUPERDEX_ASSETS_PATH to the assets folder)")
    return root.resolve()


def resolve_asset(path) -> Path:
    """The absolute path of an asset: a relative path is taken under the assets folder, an
    absolute one as it is. Raises Error naming the path when it does not exist."""
    p = Path(path)
    if p.is_absolute():
        if not p.exists():
            raise _m.Error(f"resolve_asset: {str(path)!r} does not exist")
        return p.resolve()
    root = get_assets_root()
    if not (root / p).exists():
        raise _m.Error(f"resolve_asset: {str(path)!r} not found under {str(root)!r}")
    return (root / p).resolve()


def resolve_asset_root(path) -> Path:
    """The assets folder a relative asset path resolves under: the root a prefab's own relative
    paths are written against (prefab.add_to_scene's root_path). Raises Error for an absolute
    path or a missing asset."""
    p = Path(path)
    if p.is_absolute():
        raise _m.Error(f"resolve_asset_root: {str(path)!r} must be relative to an assets folder")
    resolve_asset(p)
    return get_assets_root()
