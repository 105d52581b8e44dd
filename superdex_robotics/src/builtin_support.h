#pragma once
// What the built-in components share: their JSON parameters (parsed once at creation and again
// by configure) and the lookups from an actor to its articulation, link and DOFs.

#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"
#include "superdex/robotics/component.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::ActorHandle;
using physics::Quat;
using physics::Scene;
using physics::Vec3;

// The parameters of a built-in component: a JSON object given inline, as a file, or empty.
class ComponentParams {
 public:
  // `text`: "{...}", a path to a JSON file, or empty (no keys); `where` prefixes every error.
  ComponentParams(const std::string& text, std::string where);

  // Throws for keys not in `known` ("rate" is always accepted), listing the known ones.
  void allow_only(std::initializer_list<const char*> known) const;
  bool has(const char* key) const { return json_.contains(key) && !json_.at(key).is_null(); }
  real number(const char* key, real fallback) const;
  bool flag(const char* key, bool fallback) const;
  std::string text(const char* key, const std::string& fallback) const;
  // `n` numbers, or one number broadcast to n; null entries become NaN when `allow_null`.
  VecX vector(const char* key, int n, const VecX& fallback, bool allow_null = false) const;
  Vec3 vec3(const char* key, const Vec3& fallback) const;
  // A quaternion [x, y, z, w], normalised.
  Quat quaternion(const char* key, const Quat& fallback) const;
  const nlohmann::json& json() const { return json_; }
  // "where: key", for messages.
  std::string at(const char* key) const { return where_ + ": params." + key; }
  // Sets the component's rate from "rate" when present.
  void apply_rate(Component& component) const;

 private:
  nlohmann::json json_;
  std::string where_;
};

// The articulation of an articulated actor or of a link actor (throws for other actors).
ActorHandle articulation_of(const Scene& scene, ActorHandle actor, const std::string& where);
// A link actor (throws for other actors).
void require_link(const Scene& scene, ActorHandle actor, const std::string& where);
// The DOF slice of a link's joint.
physics::ArticulatedDofInfo joint_dofs_of_link(const Scene& scene, ActorHandle link, const std::string& where);
// The one DOF of a link's joint; throws unless the joint has exactly one DOF.
int single_dof_of_link(const Scene& scene, ActorHandle link, const std::string& where);
// Number of DOFs of the articulation's root joint (6 free, 0 welded).
int root_dofs(const Scene& scene, ActorHandle articulation);
// A link's velocity as (velocity of its origin (m/s), angular velocity (rad/s)), world: the engine
// reports its centre of mass's (Scene::velocity).
physics::Vec6 link_origin_velocity(const Scene& scene, ActorHandle link);
// The total contact torque on a link about its origin (N m, world): the engine reports it about
// the centre of mass (Scene::contact_torque). Needs the link's TotalContactForce query.
Vec3 contact_torque_about_origin(const Scene& scene, ActorHandle link);
// Link index by name; throws naming the known links.
int link_index_by_name(const Scene& scene, ActorHandle articulation, const std::string& name, const std::string& where);

// The DOF an actuator drives: the single DOF of its link's joint, and its state.
struct ActuatedDof {
  Scene scene{0};
  ActorHandle articulation = 0;
  int dof = 0;

  // from a link actor; throws unless its joint has exactly one DOF
  ActuatedDof(const Scene& scene, ActorHandle link, const std::string& where);
  real position() const { return scene.pose(articulation)[dof]; }          // rad or m
  real velocity() const { return scene.joint_velocities(articulation)[dof]; }  // rad/s or m/s
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
