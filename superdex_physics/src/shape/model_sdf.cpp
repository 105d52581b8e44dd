// model::bake_sdf (model.h): a signed-distance grid of the model's closed surface (the triangle
// mesh, or the boundary of the tetrahedral mesh), laid out by GridSdfParams.

#include <cmath>

#include "shape/model_mesh.h"
#include "shape/sdf_internal.h"
#include "shape/tet_mesh_surface.h"
#include "superdex/physics/error.h"
#include "superdex/physics/model.h"
#include "superdex/physics/params/actor_params.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The closed surface of the model's mesh.
TriangleMesh model_surface(const ModelData& d) {
  if (!d.mesh) throw Error("bake_sdf: the model has no mesh to compute a signed-distance grid of");
  const MeshData& m = *d.mesh;
  const int k = m.nodes_per_element;
  if (k != 3 && k != 4)
    throw Error("bake_sdf: mesh.nodes_per_element: a signed-distance grid needs triangles (3) or tetrahedra (4), got " + std::to_string(k));
  if (m.coordinates.size() % 3 != 0 || m.connectivity.size() % static_cast<size_t>(k) != 0)
    throw Error("bake_sdf: the mesh's coordinates or connectivity are incomplete (see model.validate)");
  for (int node : m.connectivity)
    if (node < 0 || node >= m.num_nodes()) throw Error("bake_sdf: mesh.connectivity: node " + std::to_string(node) + " out of range");
  if (k == 3) return TriangleMesh{mesh_nodes(m), mesh_elements<3>(m)};
  return tet_boundary_mesh(TetMesh{mesh_nodes(m), mesh_elements<4>(m), {}, {}});
}

// The reference length of the resolution mode (1 for Explicit: resolution_delta is in metres).
double reference_length(const TriangleMesh& s, const Eigen::Vector3d& extent, GridSdfResolutionMode mode) {
  using M = GridSdfResolutionMode;
  switch (mode) {
    case M::LargestAxis: return extent.maxCoeff();
    case M::SmallestAxis: return extent.minCoeff();
    case M::MeanAxis: return extent.mean();
    case M::Explicit: return 1.0;
    case M::LargestEdge:
    case M::SmallestEdge:
    case M::MeanEdge: {
      double lo = INFINITY, hi = 0, sum = 0;
      size_t n = 0;
      for (const auto& t : s.triangles)
        for (int k = 0; k < 3; ++k) {
          const double e = (s.vertices[t[k]] - s.vertices[t[(k + 1) % 3]]).cast<double>().norm();
          lo = std::min(lo, e), hi = std::max(hi, e), sum += e, ++n;
        }
      return mode == M::LargestEdge ? hi : mode == M::SmallestEdge ? lo : sum / static_cast<double>(n);
    }
  }
  throw Error("bake_sdf: params.resolution_mode: unknown mode " + std::to_string(static_cast<int>(mode)));
}

}  // namespace

namespace model {

void bake_sdf(ModelData& data) { bake_sdf(data, GridSdfParams{}); }

void bake_sdf(ModelData& data, const GridSdfParams& params) {
  if (!params.resolution_delta.allFinite() || (params.resolution_delta.array() <= 0).any())
    throw Error("bake_sdf: params.resolution_delta must be positive and finite on every axis");
  if (!(std::isfinite(params.boundary_padding_dist) && params.boundary_padding_dist >= 0))
    throw Error("bake_sdf: params.boundary_padding_dist must be a finite number >= 0");
  if ((params.min_grid_resolution.array() < 1).any()) throw Error("bake_sdf: params.min_grid_resolution must be >= 1 on every axis");
  const TriangleMesh surface = model_surface(data);
  if (surface.triangles.empty()) throw Error("bake_sdf: the mesh has no surface triangles");
  Eigen::Vector3d lo = surface.vertices[0].cast<double>(), hi = lo;
  for (const Vec3& p : surface.vertices) lo = lo.cwiseMin(p.cast<double>()), hi = hi.cwiseMax(p.cast<double>());
  const double reference = reference_length(surface, hi - lo, params.resolution_mode);
  const Eigen::Vector3d padded_lo = lo.array() - double(params.boundary_padding_dist);
  const Eigen::Vector3d padded_hi = hi.array() + double(params.boundary_padding_dist);
  SdfGrid grid;
  double samples = 1;
  for (int a = 0; a < 3; ++a) {
    const double voxel = reference * double(params.resolution_delta[a]);
    if (!(voxel > 0)) throw Error("bake_sdf: the mesh has no extent along the resolution mode's measure");
    const double cells = std::max<double>(params.min_grid_resolution[a], std::ceil((padded_hi[a] - padded_lo[a]) / voxel - 1e-9));
    if (cells > 4096) throw Error("bake_sdf: more than 4096 voxels along an axis: coarsen params.resolution_delta");
    grid.size[a] = static_cast<int>(cells) + 1;
    samples *= grid.size[a];
  }
  if (samples > double(1 << 27)) throw Error("bake_sdf: the grid would hold more than 2^27 samples: coarsen params.resolution_delta");
  grid.grid_min = padded_lo.cast<real>();
  grid.grid_max = padded_hi.cast<real>();
  if ((grid.grid_max.array() <= grid.grid_min.array()).any())
    throw Error("bake_sdf: the mesh is flat along an axis: give params.boundary_padding_dist > 0");
  fill_sdf(surface, grid, "bake_sdf: mesh");

  GridSdfData sdf;
  sdf.dims = Int3(grid.size[0], grid.size[1], grid.size[2]);
  sdf.values = std::move(grid.values);
  sdf.bounds = Aabb{grid.grid_min, grid.grid_max};
  sdf.negative_value_bounds = Aabb{lo.cast<real>(), hi.cast<real>()};
  data.sdf = std::move(sdf);
}

}  // namespace model
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
