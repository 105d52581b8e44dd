#pragma once
// The grid layout shared by the SDF computation and its cache, and grid sampling helpers.

#include <string>

#include "superdex/physics/sdf.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// An SdfGrid with grid_min, grid_max and size set for `mesh` and `options`, values empty.
// Cubic cells of side (longest bounding-box side) / resolution, centred on the bounding box,
// `padding_cells` beyond it on every side. Throws "<where>: ..." for bad options.
SdfGrid sdf_layout(const TriangleMesh& mesh, const SdfOptions& options, const std::string& where);

// Fills grid.values with the signed distances to `mesh` at the nodes of grid's layout (grid_min,
// grid_max and size set). Throws "<where>: ..." for a mesh that is not closed or is malformed.
void fill_sdf(const TriangleMesh& mesh, SdfGrid& grid, const std::string& where);

// Position (m) of grid node (i, j, k).
inline Vec3 sdf_node(const SdfGrid& g, int i, int j, int k) {
  const Vec3 cell = (g.grid_max - g.grid_min).cwiseQuotient(Vec3(g.size[0] - 1, g.size[1] - 1, g.size[2] - 1));
  return g.grid_min + Vec3(i, j, k).cwiseProduct(cell);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
