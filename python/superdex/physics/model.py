"""Model data files (.mochi.json, .mochi.h5, and OBJ, OFF, PLY, STL surface meshes): load, save,
check, correct and transform superdex.physics.ModelData. Every function raises
superdex.physics.Error naming the file or field at fault.

load_from_file / load_from_bytes: read, then auto_correct() and validate(); the *_unchecked forms
only read. save_to_file / save_to_json_string: write. bake_transform,
bake_coordinate_space_transform, bake_sdf, flip_winding_order: change a model in place.
"""

from superdex._native import module as _m

__all__ = [
    "load_from_file",
    "load_from_file_unchecked",
    "load_from_bytes",
    "load_from_bytes_unchecked",
    "save_to_file",
    "save_to_json_string",
    "validate",
    "auto_correct",
    "bake_transform",
    "bake_coordinate_space_transform",
    "bake_sdf",
    "flip_winding_order",
]

# the native submodule's functions, under the same names
globals().update({name: getattr(_m.model, name) for name in __all__})
