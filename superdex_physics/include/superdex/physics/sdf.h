#pragma once
/// @file sdf.h
/// Signed-distance grids computed from closed triangle meshes, and their on-disk cache.
///
/// Distances are exact point-to-triangle distances (m) in the mesh frame, negative inside;
/// the sign comes from angle-weighted pseudo-normals. The grid is axis-aligned, its cells
/// cubic: `resolution` cells span the longest side of the mesh bounding box, plus
/// `padding_cells` on every side, so that the grid border lies outside the surface.

#include <filesystem>
#include <memory>
#include <string>

#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// How a distance grid is laid out around a mesh.
struct SdfOptions {
  int resolution = 32;    ///< cells along the longest side of the mesh bounding box (>= 2)
  int padding_cells = 3;  ///< extra cells beyond the bounding box on every side (>= 1)
};

/// Computes the grid. Throws superdex::Error "<where>: computing a signed-distance field needs
/// a closed mesh: N boundary edges" for open meshes, and for bad options. Inside-out meshes are
/// handled (distances are still negative inside). Uses all TBB worker threads.
SdfGrid compute_sdf(const TriangleMesh& mesh, const SdfOptions& options, const std::string& where);

/// The grid for `mesh` from the cache when a valid entry exists, else computed and stored.
/// Entries are `.mochi.h5` files with an `sdf/` group, named by a hash of the vertex
/// coordinates, the triangles and the options. A corrupt or mismatching entry is ignored and
/// overwritten; an unwritable cache directory only disables caching.
std::shared_ptr<const SdfGrid> cached_sdf(const TriangleMesh& mesh, const SdfOptions& options, const std::string& where);

/// The cache directory: $SUPERDEX_CACHE_DIR when set and non-empty, else
/// $HOME/.cache/superdex/sdf; empty when neither is available.
std::filesystem::path sdf_cache_directory();

/// The cache file name (without directory) for a mesh and options: "<32 hex digits>.mochi.h5".
std::string sdf_cache_key(const TriangleMesh& mesh, const SdfOptions& options);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
