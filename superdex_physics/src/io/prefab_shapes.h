#pragma once
// Loading the shapes a prefab names (prefab_shapes.cpp): beyond prefab::load_shapes, loading only
// the missing ones, loading with an extra uniform scale baked in (add_to_scene from a file), and
// releasing what a load made.

#include <string>
#include <vector>

#include "superdex/physics/prefab/scene_prefab.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

/// An inline primitive scaled uniformly by `s` (> 0): radii, extents, centre, plane distance.
ShapeGeometry scaled_primitive(ShapeGeometry g, real s);
/// Loads the shapes whose handle is not valid yet (ensure_fully_loaded).
void load_missing_shapes(ScenePrefab& prefab, const std::string& root_path);
/// (Re)loads every shape with `scale` (> 0) times its nesting's scale baked in; returns the
/// handles made. On an error, those made so far are released.
std::vector<ShapeHandle> load_scaled_shapes(ScenePrefab& prefab, const std::string& root_path, real scale);

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
