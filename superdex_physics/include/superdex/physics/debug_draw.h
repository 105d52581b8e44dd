#pragma once
/// @file debug_draw.h
/// Debug drawing: a scene's contacts, bounds, frames and bodies as primitives (line segments and
/// spheres, world frame, metres) that the client renders. What is drawn is chosen by feature
/// (find_feature by name) and by actor; nothing is drawn until the master switch is on.
/// `DebugDraw` is a handle to one scene's debug drawing, obtained from Scene::debug_draw(); use it
/// on the thread that uses its scene. Every method throws superdex::Error if the scene was destroyed.

#include <memory>
#include <span>
#include <string>

#include "superdex/physics/handles.h"
#include "superdex/physics/real.h"
#include "superdex/physics/types.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Spheres: centre positions[i] (world, m), radii[i] (m), colors[i]; the three spans have one
/// length.
struct DebugDrawSpheres {
  std::span<const Real3> positions;
  std::span<const real> radii;
  std::span<const Color> colors;
  /// Element-wise equality of the viewed values (not of the views).
  bool operator==(const DebugDrawSpheres& o) const;
};

/// A line list: vertices 2k and 2k + 1 are the ends of segment k (world, m), each with a colour
/// (a segment may fade from one to the other). Both spans have one, even, length.
struct DebugDrawLineVertices {
  std::span<const Real3> positions;
  std::span<const Color> colors;
  /// Element-wise equality of the viewed values (not of the views).
  bool operator==(const DebugDrawLineVertices& o) const;
};

/// What DebugDraw::gather_data returns: views of buffers that `owner` keeps alive. The buffers
/// are never written again while held: a later gather_data writes new ones, and the scene's
/// destruction leaves them readable.
struct DebugDrawData {
  DebugDrawLineVertices line_vertices;
  DebugDrawSpheres spheres;
  /// Keeps the viewed buffers alive (null when the spans view memory of the caller's).
  std::shared_ptr<const void> owner;
  /// Equality of the primitives; the owners are not compared.
  bool operator==(const DebugDrawData& o) const { return line_vertices == o.line_vertices && spheres == o.spheres; }
};

/// One scene's debug drawing (see the file comment). Off by default, with every feature off and
/// every actor on. Features are addressed by index in [0, num_features()).
class DebugDraw {
 public:
  explicit DebugDraw(SceneHandle scene) : scene_(scene) {}
  SceneHandle scene() const { return scene_; }

  /// The master switch: while off, gather_data returns empty data; feature and actor settings
  /// are kept.
  bool is_enabled() const;
  void enable(bool enable);

  int num_features() const;
  /// The index of the feature named `name` (case sensitive), or -1.
  int find_feature(const std::string& name) const;
  /// Throw superdex::Error naming `index` and the valid range when it is out of range.
  std::string feature_name(int index) const;
  std::string feature_description(int index) const;
  bool is_feature_enabled(int index) const;
  /// Switches one feature; remembered while the master switch is off.
  void enable_feature(int index, bool enable);

  /// Whether the actor's primitives are drawn: all actors are by default. Disabling an
  /// articulation disables its links too; a contact is drawn when both its actors are.
  /// Throws superdex::Error for an actor not in the scene.
  void enable_actor(ActorHandle actor, bool enable);
  bool is_actor_enabled(ActorHandle actor) const;

  /// The primitives of the enabled features and actors, from the scene's current state (contact
  /// features: the contacts of the last step). Empty when the master switch is off.
  DebugDrawData gather_data();

 private:
  SceneHandle scene_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
