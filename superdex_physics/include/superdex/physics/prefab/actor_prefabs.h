#pragma once
/// @file actor_prefabs.h
/// The actors of a prefab (SuperDex's RigidActorPrefab, SoftActorPrefab, ArticulatedActorPrefab
/// and its links and joints): the params that create each actor, with the shape named by a file
/// (loaded by prefab::load_shapes) and the placement given relative to the prefab's frame P
/// instead of the world. Lengths in m; rotations are quaternions stored [x, y, z, w].

#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/articulation_desc.h"
#include "superdex/physics/params/actor_params.h"
#include "superdex/physics/shape.h"
#include "superdex/physics/types.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

/// Where an actor's (or link's) shape comes from: a model file, or an inline primitive that a
/// prefab file wrote in place (`"shape": {"box": {...}}`), and what is baked into it when loaded:
/// the per-axis scale first, then the rotation and translation (shape frame S in the actor frame L).
struct ShapeSource {
  /// Path as written: "./x" relative to the prefab file's folder, "x" to the root path, absolute
  /// as is (prefab::get_prefab_full_path). Empty: `primitive`, or the params' `shape` handle.
  std::string file;
  /// An inline primitive, used when `file` is empty. Its rotation and translation are not baked
  /// but kept as the shape's pose in the link frame (articulated links only).
  std::optional<ShapeGeometry> primitive;
  Real3 scale = Real3::Ones();                    ///< per axis, non-zero
  Quaternion rotation = Quaternion::Identity();   ///< R_LS
  Real3 translation = Real3::Zero();              ///< p_LoSo_L (m, before the prefab's scale)
};
bool operator==(const ShapeSource& a, const ShapeSource& b);

/// A model shown in place of the collision shape (a `.glb`, for the debugger); not simulated.
struct RenderModel {
  std::string file;                               ///< path, resolved as ShapeSource::file
  Real3 scale = Real3::Ones();
  Quaternion rotation = Quaternion::Identity();   ///< in the actor (link) frame
  Real3 translation = Real3::Zero();              ///< m, in the actor (link) frame
  bool operator==(const RenderModel& o) const {
    return file == o.file && scale == o.scale && rotation.coeffs() == o.rotation.coeffs() && translation == o.translation;
  }
};

/// A rigid actor: RigidActorParams whose `world_from_local` is replaced by rotation/translation
/// in the prefab frame (X_PL) and whose `shape` is loaded from `shape_source`.
struct RigidActorPrefab : RigidActorParams {
  std::optional<std::string> comment;
  ShapeSource shape_source;
  Quaternion rotation = Quaternion::Identity();   ///< R_PL, non-zero
  Real3 translation = Real3::Zero();              ///< p_PoLo_P (m)
  RenderModel render_model;
};

/// A soft actor: SoftActorParams placed and shaped as RigidActorPrefab (the scale must be
/// positive: a tetrahedral mesh cannot be mirrored). This engine adds pinned nodes and reduced
/// models to what SuperDex's soft prefab holds.
struct SoftActorPrefab : SoftActorParams {
  std::optional<std::string> comment;
  ShapeSource shape_source;
  ColliderType collider_type = ColliderType::Auto;  ///< experimental; only Auto is simulated
  GridSdfParams sdf;                                ///< experimental; unused by this engine
  std::string flow_file;                            ///< experimental deep flow shape; not supported yet
  ShapeHandle flow;
  bool use_recentering = true;                      ///< RecenteringParams::use_recentering
  Quaternion rotation = Quaternion::Identity();     ///< R_PL
  Real3 translation = Real3::Zero();                ///< p_PoLo_P (m)
  RenderModel render_model;
  std::vector<int> fixed_nodes;                     ///< pinned node indices into the tet mesh
  std::optional<Aabb> fixed_region;                 ///< nodes inside it (frame L, m, before scaling) are pinned
  int reduced_modes = 0;                            ///< SoftMaterial::reduced_modes (0: the full model)
};

/// A joint of an articulated prefab: exactly ArticulatedJointParams.
struct ArticulatedJointPrefab : ArticulatedJointParams {
  bool operator==(const ArticulatedJointPrefab&) const = default;
};

/// A link of an articulated prefab: ArticulatedLinkParams with its shape loaded from `shape_source`
/// (SuperDex's shape_file, shape_scale, shape_rotation, shape_translation).
struct ArticulatedLinkPrefab : ArticulatedLinkParams {
  ShapeSource shape_source;
  RenderModel render_model;
  bool operator==(const ArticulatedLinkPrefab&) const = default;
};

/// An articulated actor. Its uniform `scale` multiplies the link shapes and joint offsets (not
/// rotation/translation); X_PR = (rotation, translation) places the root joint's parent frame R.
struct ArticulatedActorPrefab {
  std::optional<std::string> comment;
  std::string name;                               ///< empty: "articulation"
  real scale = 1;                                 ///< > 0
  Quaternion rotation = Quaternion::Identity();   ///< R_PR
  Real3 translation = Real3::Zero();              ///< p_PoRo_P (m)
  std::vector<ArticulatedCycleJointParams> cycles;
  std::vector<ArticulatedJointPrefab> joints;     ///< one per link
  std::vector<ArticulatedLinkPrefab> links;       ///< parents first
  std::optional<std::vector<real>> joint_velocities;  ///< one per DOF (m/s, rad/s)
  /// This engine's additions, from `.superdex_bot` files: the initial joint positions (bot-DOF
  /// order, root joint excluded; empty: zero) and link pairs whose contact differs from the default.
  std::vector<real> default_pose;
  std::vector<ContactOverride> contact_overrides;
  /// The `.superdex_bot` file the links and joints were read from, as written; saved in place of
  /// them. Empty: they are written inline.
  std::string bot_file;
  bool operator==(const ArticulatedActorPrefab& o) const;
};

/// The actors of a prefab, by type, each list in creation order.
struct ActorLists {
  std::optional<std::string> comment;
  std::vector<ArticulatedActorPrefab> articulated;
  std::vector<RigidActorPrefab> rigid;
  std::vector<SoftActorPrefab> soft;
};

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
