// Shapes from model data, geometry or tet meshes: the geometry a rigid body carries, the volume
// mesh soft bodies use, the model itself, and the compact triangle surface.

#include <algorithm>

#include "shape/model_mesh.h"
#include "shape/shape_data.h"
#include "shape/tet_mesh_surface.h"
#include "superdex/physics/error.h"
#include "superdex/physics/mesh_shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The triangles over only the nodes they use, those kept in increasing order of their index.
std::shared_ptr<const MeshData> compact_surface(const std::vector<Vec3>& nodes, const std::vector<std::array<int, 3>>& triangles) {
  std::vector<int> remap(nodes.size(), -1);
  for (const auto& t : triangles)
    for (int i : t) remap[i] = 0;
  std::vector<Vec3> used;
  for (size_t i = 0; i < nodes.size(); ++i)
    if (remap[i] == 0) {
      remap[i] = static_cast<int>(used.size());
      used.push_back(nodes[i]);
    }
  std::vector<std::array<int, 3>> tris = triangles;
  for (auto& t : tris)
    for (int& i : t) i = remap[i];
  return std::make_shared<const MeshData>(mesh_data(used, tris));
}

// The 8 corners and 12 outward triangles of an oriented box.
TriangleMesh box_mesh(const Box& box) {
  TriangleMesh m;
  const Quat q = box.rotation.normalized();
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1 ? 1 : -1) * box.half_extents.x(), (i & 2 ? 1 : -1) * box.half_extents.y(), (i & 4 ? 1 : -1) * box.half_extents.z());
    m.vertices.push_back(box.center + q * corner);
  }
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

}  // namespace

ShapeMeshes meshes_of(const ShapeData& data) {
  auto part = [&](const std::optional<MeshData>& m) { return m ? std::shared_ptr<const MeshData>(data.model, &*m) : nullptr; };
  return ShapeMeshes{part(data.model->mesh), data.surface, part(data.model->visual_mesh)};
}

std::shared_ptr<ShapeData> shape_from_tet_mesh(TetMesh mesh, const std::string& where) {
  const int n = static_cast<int>(mesh.nodes.size());
  if (mesh.tets.empty()) throw Error(where + ": the tet mesh has no tetrahedra");
  for (int i = 0; i < n; ++i)
    if (!mesh.nodes[i].allFinite()) throw Error(where + ": node " + std::to_string(i) + " has non-finite coordinates");
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    for (int k = 0; k < 4; ++k)
      if (tet[k] < 0 || tet[k] >= n)
        throw Error(where + ": tetrahedron " + std::to_string(t) + " refers to node " + std::to_string(tet[k]) + ", out of range (" +
                    std::to_string(n) + " nodes)");
    Mat3 D;
    D << mesh.nodes[tet[1]] - mesh.nodes[tet[0]], mesh.nodes[tet[2]] - mesh.nodes[tet[0]], mesh.nodes[tet[3]] - mesh.nodes[tet[0]];
    const real volume = D.determinant() / 6;
    const real scale = std::max({D.col(0).norm(), D.col(1).norm(), D.col(2).norm()});
    if (volume < 0) throw Error(where + ": tetrahedron " + std::to_string(t) + " is inverted (negative volume)");
    if (!(volume > real(1e-9) * scale * scale * scale)) throw Error(where + ": tetrahedron " + std::to_string(t) + " is degenerate (volume ~ 0)");
  }
  auto data = std::make_shared<ShapeData>();
  ModelData model;
  model.mesh = mesh_data(mesh.nodes, mesh.tets);
  data->model = std::make_shared<const ModelData>(std::move(model));
  data->surface = compact_surface(mesh.nodes, tet_boundary_faces(mesh.tets));
  data->tet_mesh = std::make_shared<const TetMesh>(std::move(mesh));
  data->geometry = tet_mesh_boundary_shape(*data->tet_mesh, where);
  return data;
}

std::shared_ptr<ShapeData> shape_from_geometry(const ShapeGeometry& geometry) {
  auto data = std::make_shared<ShapeData>();
  data->geometry = geometry;
  ModelData model;
  if (const auto* p = std::get_if<PlaneShape>(&geometry)) {
    model.plane = Plane{p->normal, p->distance};
  } else if (const auto* s = std::get_if<SphereShape>(&geometry)) {
    model.sphere = Sphere{s->center, s->radius};
  } else if (const auto* b = std::get_if<BoxShape>(&geometry)) {
    model.box = Box{Real3::Zero(), b->half_extents, Quaternion::Identity()};
  } else if (const auto* m = std::get_if<MeshShape>(&geometry)) {
    model.mesh = mesh_data(m->mesh->vertices, m->mesh->triangles);
    data->surface = compact_surface(m->mesh->vertices, m->mesh->triangles);
  }
  // capsules have no model counterpart: their model is empty
  data->model = std::make_shared<const ModelData>(std::move(model));
  return data;
}

std::shared_ptr<ShapeData> shape_from_model(ModelData model, const std::string& where) {
  try {
    model::validate(model);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  std::shared_ptr<ShapeData> data;
  if (model.mesh && !model.mesh->is_empty() && model.mesh->nodes_per_element == 4) {
    data = shape_from_tet_mesh(TetMesh{mesh_nodes(*model.mesh), mesh_elements<4>(*model.mesh), {}, {}}, where + ": mesh");
  } else if (model.mesh && !model.mesh->is_empty() && model.mesh->nodes_per_element == 3) {
    const ShapeGeometry g = make_mesh_shape(TriangleMesh{mesh_nodes(*model.mesh), mesh_elements<3>(*model.mesh)}, where + ": mesh");
    data = shape_from_geometry(g);
  } else if (model.box) {
    const Box& b = *model.box;
    // a box centred and aligned with the model frame is a primitive; any other one, its mesh
    const bool aligned = b.center.isZero(0) && b.rotation.normalized().angularDistance(Quaternion::Identity()) == 0;
    data = shape_from_geometry(aligned ? ShapeGeometry(BoxShape{b.half_extents}) : ShapeGeometry(make_mesh_shape(box_mesh(b), where + ": box")));
  } else if (model.sphere) {
    data = shape_from_geometry(SphereShape{model.sphere->center, model.sphere->radius});
  } else if (model.plane) {
    data = shape_from_geometry(PlaneShape{model.plane->normal.normalized(), model.plane->distance});
  } else {
    // polylines and distance grids alone: nothing a rigid or soft body can carry
    data = std::make_shared<ShapeData>();
  }
  if (data->geometry) validate_shape(*data->geometry, where);
  data->model = std::make_shared<const ModelData>(std::move(model));
  return data;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
