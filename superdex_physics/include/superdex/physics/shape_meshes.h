#pragma once
/// @file shape_meshes.h
/// The meshes of a shape (engine.h's shape_meshes) or of an actor (Scene::meshes).

#include <memory>

#include "superdex/physics/model.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// The meshes of a shape or of an actor's shape, shared and immutable (they stay valid after the
/// shape's release); null where there is none.
struct ShapeMeshes {
  /// The model's main mesh (a shape's) or the simulation mesh (an actor's: a soft actor's
  /// tetrahedra, a rigid actor's compact surface).
  std::shared_ptr<const MeshData> mesh;
  /// The triangle surface over the nodes it uses only, in increasing order of their mesh index.
  std::shared_ptr<const MeshData> surface;
  /// The model's visual mesh.
  std::shared_ptr<const MeshData> visual;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
