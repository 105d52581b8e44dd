#pragma once
/// @file contact_params.h
/// The contact parameters of an actor's surface, and how its collision geometry is derived.

#include <string>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// How OTHER actors detect contact with an actor (it does not change how the actor itself
/// detects others).
enum class ColliderType {
  None,        ///< no collision geometry: nothing detects contact with this actor
  Auto,        ///< chosen from the shape: sphere, plane, box or capsule primitives as themselves,
               ///< meshes by their distance field (Sdf)
  Sphere,      ///< the ball bounding the shape (rigid actors and links)
  Box,         ///< the shape's bounding box in the actor frame (rigid actors and links)
  Mesh,        ///< the surface mesh itself (rigid actors and links)
  Plane,       ///< an infinite plane (static rigid actors carrying a plane shape)
  Sdf,         ///< a signed-distance grid of the closed surface mesh
  PointCloud,  ///< sample points (rods and shells); not available in this engine
};

/// "None", "Auto", "Sphere", ... as written in files.
const char* collider_type_name(ColliderType type);

/// Contact parameters of an actor's surface (SuperDex's fields and defaults; SI units). A contact
/// pair combines the two sides' Coulomb friction by their geometric mean (a side with 0 disables
/// friction).
///
/// How this engine's implicit solve uses them: contact is near-rigid (each contact point's normal
/// impulse keeps the gap from closing, regularised as the solver's near-rigid setting says), or
/// compliant with this engine's contact_stiffness and dissipation_time_scale, with Coulomb
/// friction coulomb_friction_coefficient. The penalty law of the other fields (force =
/// penalty_coefficient x area x depth below penalty_threshold_default, smoothed, with viscous
/// terms) is not the model this engine solves: they are kept, validated and returned, and an actor
/// created with a value other than the default logs one warning naming the field.
struct ContactParams {
  real penalty_coefficient = real(1e9);            ///< Pa/m, > 0
  real penalty_smoothing_half_distance = real(0.005);  ///< m, >= 0
  real penalty_threshold_default = real(0.001);    ///< m (may be negative)
  real penalty_threshold_extra_padding = 0;        ///< m, >= 0
  bool friction_with_collider_normal = true;       ///< friction in the collider's tangent plane (else the colliding surface's)
  real max_alignment_normals = 0;                  ///< in [-1, 1]: points whose normal agrees with the collider's beyond it take no contact
  real viscous_friction_coefficient = 0;           ///< s/m, >= 0
  real coulomb_friction_coefficient = real(0.5);   ///< >= 0
  real friction_falloff_vel = real(0.01);          ///< m/s, >= 0
  real normal_viscous_damping_coefficient = 0;     ///< s/m, >= 0
  real distance_error_bound = 0;                   ///< m, >= 0: padding of the collider's bounds when culling pairs
  real obj_scale = 1;                              ///< > 0: scale of approximate (learned) distance fields; 1 for exact ones
  real colliding_penalty_length_scale = 1;         ///< m, > 0: penalty correction for contact lumped on lines or points
  // this engine's additions: compliant contact
  real contact_stiffness = 0;       ///< N/m per contact point, >= 0; 0: near-rigid (the solver's regularisation)
  real dissipation_time_scale = 0;  ///< s, >= 0: normal damping = contact_stiffness x this (with a stiffness)
  /// The contact detection threshold (m): the default plus, when `add_padding`, the extra padding.
  real penalty_threshold_dist(bool add_padding) const {
    return penalty_threshold_default + (add_padding ? penalty_threshold_extra_padding : real(0));
  }
  bool operator==(const ContactParams&) const = default;
};

/// Throws superdex::Error naming `where`.field for an invalid value.
void validate(const ContactParams& params, const std::string& where);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
