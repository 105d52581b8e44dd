#pragma once
/// @file recording_params.h
/// What a scene recording (Scene::start_recording, an HDF5 file: docs/recording_format.md)
/// writes. SuperDex's fields and defaults.

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// The parts of a scene recording. Per actor, once, when the recording first sees it: meshes,
/// DOF map, mass matrix. Per step: states, targets, contacts.
struct RecordingParams {
  /// The actor's meshes in its own frame (a rigid body's or link's surface, a soft actor's
  /// tetrahedra and surface).
  bool record_actor_meshes = true;
  /// Where the actor's DOFs sit in the scene's DOF vector (every actor's DOFs in creation order).
  bool record_actor_local_to_global_map = false;
  /// The articulated actor's joint-space mass matrix (kg, kg m, kg m^2), a soft actor's node
  /// masses (kg), when first seen.
  bool record_actor_mass_matrix = false;
  /// Joint and link drive targets and gains of articulated actors, every step.
  bool record_target_state = true;
  /// Pose and velocities of dynamic bodies, joint positions and velocities of articulations, node
  /// displacements and velocities of soft actors, every step.
  bool record_dynamic_actor_state = true;
  /// The same for static bodies.
  bool record_static_actor_state = false;
  /// The step's contact points: actors, positions, normals and forces.
  bool record_contact_points = false;
  /// The contact force on every node of each soft actor (N, world).
  bool record_node_contact_forces = false;
  /// The signed gap (m) at each contact point before the step.
  bool record_sdf_distances = false;

  /// Every part on (or off).
  static RecordingParams all(bool enabled = true) {
    RecordingParams p;
    p.record_actor_meshes = p.record_actor_local_to_global_map = p.record_actor_mass_matrix = enabled;
    p.record_target_state = p.record_dynamic_actor_state = p.record_static_actor_state = enabled;
    p.record_contact_points = p.record_node_contact_forces = p.record_sdf_distances = enabled;
    return p;
  }
  bool operator==(const RecordingParams&) const = default;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
