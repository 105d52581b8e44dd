// Loading the shapes a prefab names into shape handles (prefab.h load_shapes, prefab_shapes.h):
// files with their scale, rotation and translation baked in, inline primitives scaled, each with
// the uniform scale of the prefabs enclosing it.

#include <cmath>

#include "io/prefab_json.h"
#include "io/prefab_shapes.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/error.h"
#include "superdex/physics/file_path.h"
#include "superdex/physics/mesh_shape.h"
#include "superdex/physics/prefab.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

ShapeGeometry scaled_primitive(ShapeGeometry g, real s) {
  if (auto* x = std::get_if<SphereShape>(&g)) x->radius *= s, x->center *= s;
  if (auto* x = std::get_if<BoxShape>(&g)) x->half_extents *= s;
  if (auto* x = std::get_if<CapsuleShape>(&g)) x->radius *= s, x->half_length *= s;
  if (auto* x = std::get_if<PlaneShape>(&g)) x->distance *= s;
  return g;
}

namespace {

struct ShapeLoader {
  const std::string& root;
  bool only_missing;
  std::vector<ShapeHandle> made;

  // The bake of a shape file: its own scale times the prefab's `s`, then its pose (m scaled by s).
  ShapeBake bake(const ShapeSource& src, real s, const std::string& where, bool mirroring_allowed) const {
    if (!src.scale.allFinite() || (src.scale.array() == 0).any())
      throw Error(where + ".scale: must be finite and non-zero, got [" + std::to_string(src.scale.x()) + ", " +
                  std::to_string(src.scale.y()) + ", " + std::to_string(src.scale.z()) + "]");
    if ((src.scale.array() < 0).any())
      throw Error(where + ".scale: must be positive" + (mirroring_allowed ? " (mirroring is not supported yet)" : " (a tetrahedral mesh cannot be mirrored)"));
    if (!(src.rotation.norm() > real(1e-6))) throw Error(where + ".shape_rotation: must be a non-zero quaternion");
    ShapeBake b;
    b.scale = src.scale * s;
    b.rotation = src.rotation.normalized();
    b.translation = src.translation * s;
    return b;
  }
  std::string existing_file(const ShapeSource& src, const ScenePrefab& p, const std::string& where) const {
    const std::string path = get_prefab_full_path(src.file, root, p.source_file);
    if (!is_existing_file(path)) throw Error(where + ".shape: shape file '" + path + "' does not exist");
    return path;
  }
  ShapeHandle keep(ShapeHandle h) {
    made.push_back(h);
    return h;
  }

  // The shape file `src` names, loaded as load_shape_from_file does (any format it reads), with
  // the bake; errors name the prefab field.
  ShapeHandle file_shape(const ShapeSource& src, const ScenePrefab& p, real s, const std::string& where, bool mirroring_allowed) {
    const ShapeBake b = bake(src, s, where, mirroring_allowed);
    const std::string path = existing_file(src, p, where);
    try {
      return keep(load_shape_from_file(path, b));
    } catch (const Error& e) {
      throw Error(where + ".shape: " + e.what());
    }
  }

  // a rigid body's or a link's shape; a link's primitive keeps its pose (applied at creation)
  ShapeHandle rigid_shape(const ShapeSource& src, const ScenePrefab& p, real s, const std::string& where, bool pose_kept) {
    if (!src.file.empty()) return file_shape(src, p, s, where, true);
    if (src.scale != Real3::Ones()) throw Error(where + ".scale: inline primitives take only the prefab's uniform scale");
    if (!pose_kept && (src.rotation.coeffs() != Quaternion::Identity().coeffs() || !src.translation.isZero()))
      throw Error(where + ".shape_rotation: an inline primitive of a rigid actor is centred and unrotated (use a model file)");
    const ShapeGeometry g = scaled_primitive(*src.primitive, s);
    validate_shape(g, where + ".shape");
    return keep(create_shape(g));
  }

  void load(ScenePrefab& p, real s) {
    const std::string at = error_prefix(p);
    auto wanted = [&](const ShapeHandle& h, const ShapeSource& src) {
      return (src.primitive || !src.file.empty()) && !(only_missing && h.is_valid());
    };
    for (size_t i = 0; i < p.actors.rigid.size(); ++i) {
      RigidActorPrefab& a = p.actors.rigid[i];
      if (wanted(a.shape, a.shape_source)) a.shape = rigid_shape(a.shape_source, p, s, at + "actors.rigid[" + std::to_string(i) + "]", false);
    }
    for (size_t i = 0; i < p.actors.soft.size(); ++i) {
      SoftActorPrefab& a = p.actors.soft[i];
      if (!wanted(a.shape, a.shape_source)) continue;
      const std::string where = at + "actors.soft[" + std::to_string(i) + "]";
      if (a.shape_source.file.empty()) throw Error(where + ".shape: soft actors need a tetrahedral mesh file");
      a.shape = file_shape(a.shape_source, p, s, where, false);
      if (!is_tet_mesh_shape(a.shape))
        throw Error(where + ".shape: '" + existing_file(a.shape_source, p, where) + "' has no tetrahedral mesh (soft actors need one)");
    }
    for (size_t i = 0; i < p.actors.articulated.size(); ++i) {
      ArticulatedActorPrefab& a = p.actors.articulated[i];
      const std::string where = at + "actors.articulated[" + std::to_string(i) + "]";
      if (!(a.scale > 0) || !std::isfinite(a.scale)) throw Error(where + ".scale: must be a positive number");
      for (size_t k = 0; k < a.links.size(); ++k) {
        ArticulatedLinkPrefab& l = a.links[k];
        if (wanted(l.shape, l.shape_source)) l.shape = rigid_shape(l.shape_source, p, s * a.scale, where + ".links[" + std::to_string(k) + "]", true);
      }
    }
    for (PrefabReference& ref : p.prefabs)
      if (!ref.loaded.empty()) load(ref.loaded[0], s * ref.scale);
  }
};

std::vector<ShapeHandle> load_all(ScenePrefab& prefab, const std::string& root, real scale, bool only_missing) {
  ShapeLoader loader{root, only_missing, {}};
  try {
    loader.load(prefab, scale);
  } catch (...) {
    for (const ShapeHandle& h : loader.made) release_shape(h);
    throw;
  }
  return loader.made;
}

}  // namespace

void load_shapes(ScenePrefab& prefab, const std::string& root_path) { load_all(prefab, root_path, 1, false); }

void load_missing_shapes(ScenePrefab& prefab, const std::string& root_path) { load_all(prefab, root_path, 1, true); }

std::vector<ShapeHandle> load_scaled_shapes(ScenePrefab& prefab, const std::string& root_path, real scale) {
  return load_all(prefab, root_path, scale, false);
}

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
