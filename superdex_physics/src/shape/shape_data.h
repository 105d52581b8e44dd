#pragma once
// What a registered shape holds (engine.h's ShapeHandle names one), and how it is made from model
// data (superdex/physics/model.h), from geometry given directly, or from a tet mesh.

#include <memory>
#include <optional>
#include <string>

#include "superdex/physics/model.h"
#include "superdex/physics/shape.h"
#include "superdex/physics/shape_meshes.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Immutable once registered: actors share it with the registry.
struct ShapeData {
  // the geometry a rigid body carries: a primitive, or a triangle mesh (a tet mesh's boundary);
  // none for polylines and distance grids without a surface
  std::optional<ShapeGeometry> geometry;
  // the volume mesh soft bodies use (tet meshes only)
  std::shared_ptr<const TetMesh> tet_mesh;
  // the model the shape was made from (main mesh, visual mesh, primitive, ...): never null
  std::shared_ptr<const ModelData> model = std::make_shared<const ModelData>();
  // the compact triangle surface: the nodes the triangles use only, in increasing order of their
  // index in the main mesh (null for primitives and polylines)
  std::shared_ptr<const MeshData> surface;
};

struct ShapeEntry {
  std::shared_ptr<const ShapeData> data;
  int references = 1;  // the ShapeHandles that name it
};

// The shape's model mesh, compact surface and visual mesh, each sharing ownership of the data.
ShapeMeshes meshes_of(const ShapeData& data);

// A shape from model data (validated first: errors are "<where>: <field>: ...").
std::shared_ptr<ShapeData> shape_from_model(ModelData model, const std::string& where);
// A shape from validated geometry (primitives, triangle meshes), its model made from it.
std::shared_ptr<ShapeData> shape_from_geometry(const ShapeGeometry& geometry);
// A shape from a tet mesh (checked: indices in range, every tetrahedron positively oriented and
// not degenerate; errors name `where` and the tetrahedron), its model made from it.
std::shared_ptr<ShapeData> shape_from_tet_mesh(TetMesh mesh, const std::string& where);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
