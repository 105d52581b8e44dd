// The pose controller of an articulated actor (scene.h, pose_controller_params.h): the
// constraints it owns (a link's centre of mass to its target position, the link to its target
// rotation, a joint to its target values), their gains, targets in joint and link form, and the
// generalized force they applied.

#include <cmath>
#include <string>

#include "core/spatial.h"
#include "multibody/kinematics.h"
#include "scene/actor_lookup.h"
#include "scene/articulation_poses.h"
#include "scene/step_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

PoseController& controller(Articulation& a, const char* what) {
  if (!a.pose_controller)
    throw Error(std::string(what) + ": " + describe(a.handle) + " has no pose controller; call add_articulated_pose_controller first");
  return *a.pose_controller;
}

// An array of gains: empty, one entry (for every link) or one per link; each entry valid.
void check_tracking(const std::vector<PoseTrackingParams>& p, int num_links, const std::string& what, const char* field) {
  const int n = static_cast<int>(p.size());
  if (n > 1 && n != num_links)
    throw Error(what + ": " + field + " must hold no entry, one (for every link) or one per link (" + std::to_string(num_links) + "), got " +
                std::to_string(n));
  for (int i = 0; i < n; ++i) {
    const std::string name = what + ": " + field + "[" + std::to_string(i) + "]";
    if (!(std::isfinite(p[i].stiffness) && p[i].stiffness >= 0)) throw Error(name + ".stiffness must be finite and >= 0");
    if (!(std::isfinite(p[i].damping) && p[i].damping >= 0)) throw Error(name + ".damping must be finite and >= 0");
    if (!std::isfinite(p[i].saturation) || p[i].saturation == 0)
      throw Error(name + ".saturation must be finite and not 0 (negative: no cap; positive: the force cap)");
  }
}

// Entry `link` of an array of gains (broadcast or empty: see check_tracking).
PoseTrackingParams tracking_of(const std::vector<PoseTrackingParams>& p, int link) {
  if (p.empty()) return {};
  return p.size() == 1 ? p[0] : p[link];
}

const std::vector<PoseTrackingParams>& slice_of(const PoseControllerParams& p, PoseConstraintType type) {
  return type == PoseConstraintType::LinkTranslation ? p.link_pos_tracking
         : type == PoseConstraintType::LinkRotation  ? p.link_rot_tracking
                                                     : p.joint_tracking;
}

void check_params(const PoseControllerParams& p, int num_links, const std::string& what) {
  check_tracking(p.link_pos_tracking, num_links, what, "link_pos_tracking");
  check_tracking(p.link_rot_tracking, num_links, what, "link_rot_tracking");
  check_tracking(p.joint_tracking, num_links, what, "joint_tracking");
}

// The joint rotation of a spherical or free joint in a pose, and the DOF its rotation starts at.
int rotation_dof(const JointModel& j) { return j.v_offset + (j.type == JointType::Free ? 3 : 0); }

// Points the controller's constraints at a pose and link frames (their targets now).
void aim(SceneData& s, const Articulation& a, const PoseController& pc, const VecX& pose, const std::vector<Transform>& links) {
  for (const PoseConstraintInfo& info : pc.info) {
    ConstraintRecord& c = s.constraints.at(info.handle);
    switch (info.type) {
      case PoseConstraintType::LinkTranslation: c.target_transform = links[info.link]; break;
      case PoseConstraintType::LinkRotation: c.target_rotation = links[info.link].rotation; break;
      case PoseConstraintType::Joint: {
        const JointModel& j = a.model.joints[info.link];
        if (j.nv == 1) {
          c.target_value = pose[j.v_offset];
        } else {
          c.target_rotation = quat_exp(pose.segment<3>(rotation_dof(j)));
        }
        break;
      }
      default: break;
    }
  }
}

void check_pose(const Articulation& a, const VecX& pose, const char* what, const char* arg) {
  if (pose.size() != a.model.nv)
    throw Error(std::string(what) + ": " + arg + " must hold one value per DOF (" + std::to_string(a.model.nv) + "), got " +
                std::to_string(pose.size()));
  if (!pose.allFinite()) throw Error(std::string(what) + ": " + arg + " must be finite");
}

void check_links(const Articulation& a, std::span<const TransformRT> X_WL, const char* what) {
  if (static_cast<int>(X_WL.size()) != a.model.num_links)
    throw Error(std::string(what) + ": world_from_targets must hold one transform per link (" + std::to_string(a.model.num_links) + "), got " +
                std::to_string(X_WL.size()));
  for (size_t i = 0; i < X_WL.size(); ++i)
    if (!X_WL[i].translation.allFinite() || !X_WL[i].rotation.coeffs().allFinite() || X_WL[i].rotation.norm() < real(1e-6))
      throw Error(std::string(what) + ": world_from_targets[" + std::to_string(i) + "] must be finite with a non-zero rotation");
}

void set_pose_target(SceneData& s, Articulation& a, const VecX& pose) {
  PoseController& pc = *a.pose_controller;
  pc.target_pose = pose;
  pc.target_links = link_frames_at(a, pose);
  aim(s, a, pc, pc.target_pose, pc.target_links);
}

void set_link_target(SceneData& s, Articulation& a, std::span<const TransformRT> X_WL) {
  PoseController& pc = *a.pose_controller;
  pc.target_pose = pose_from_link_frames(a, X_WL);
  pc.target_links.clear();
  for (const TransformRT& X : X_WL) pc.target_links.push_back({X.rotation.normalized(), X.translation});
  aim(s, a, pc, pc.target_pose, pc.target_links);
}

}  // namespace

void apply_pose_controller_velocities(SceneData& s, real dt) {
  for (auto& ap : s.articulations) {
    Articulation& a = *ap;
    if (!a.pose_controller || !a.pose_controller->target_velocity) continue;
    PoseController& pc = *a.pose_controller;
    // where the target was dt ago: the joint pose moved back along the velocity, each link
    // target moved by its link's motion between those two poses
    const VecX old_pose = pose_plus_delta(a.model, pc.target_pose, -dt * *pc.target_velocity);
    const std::vector<Transform> at = link_frames_at(a, pc.target_pose), before = link_frames_at(a, old_pose);
    std::vector<Transform> old_links(at.size());
    for (size_t i = 0; i < at.size(); ++i) old_links[i] = before[i] * at[i].inverse() * pc.target_links[i];
    aim(s, a, pc, old_pose, old_links);
    for (const PoseConstraintInfo& info : pc.info) settle_constraint_targets(s.constraints.at(info.handle));
    aim(s, a, pc, pc.target_pose, pc.target_links);
    pc.target_velocity.reset();
  }
}

void Scene::add_pose_controller(ActorHandle h, const PoseControllerParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "add_articulated_pose_controller";
  Articulation& a = articulated(s, h, what.c_str());
  if (a.pose_controller) throw Error(what + ": " + describe(h) + " has a pose controller already");
  const ArticulationModel& m = a.model;
  check_params(p, m.num_links, what);
  PoseController pc;
  const auto add = [&](ConstraintRecord c, PoseConstraintType type, int link) {
    const PoseTrackingParams t = tracking_of(slice_of(p, type), link);
    c.handle = next_handle();
    c.owner = h;
    c.stiffness = t.stiffness, c.damping = t.damping, c.saturation = t.saturation;
    pc.info.push_back({c.handle, type, link, m.parent[link]});
    s.constraints.emplace(c.handle, std::move(c));
  };
  // each link's centre of mass to the target's, each link's rotation to the target's
  for (int i = 0; i < m.num_links; ++i) {
    ConstraintRecord c;
    c.type = ConstraintType::RigidPivotToRigidTarget;
    c.actor_a = a.link_handles[i];
    c.p_A = m.inertia[i].com;
    add(std::move(c), PoseConstraintType::LinkTranslation, i);
  }
  for (int i = 0; i < m.num_links; ++i) {
    ConstraintRecord c;
    c.type = ConstraintType::RigidPivotRotation;
    c.actor_a = a.link_handles[i];
    add(std::move(c), PoseConstraintType::LinkRotation, i);
  }
  // each joint with DOFs on its one DOF or its rotation (a free joint's translation is left to
  // the root link's translation tracking)
  for (int i = 0; i < m.num_links; ++i) {
    const JointModel& j = m.joints[i];
    ConstraintRecord c;
    c.actor_a = h;
    c.joint = i;
    if (j.nv == 1) {
      c.type = ConstraintType::ArticulatedSingleDofTarget;
      c.dof = j.v_offset;
    } else if (j.type == JointType::Spherical || j.type == JointType::Free) {
      c.type = ConstraintType::Articulated3dRotationTarget;
      c.dof = rotation_dof(j);
    } else {
      continue;
    }
    add(std::move(c), PoseConstraintType::Joint, i);
  }
  a.pose_controller = std::move(pc);
  // the target: the pose now, moving with the joints' velocities now
  set_pose_target(s, a, pose(h));
  for (const PoseConstraintInfo& info : a.pose_controller->info) settle_constraint_targets(s.constraints.at(info.handle));
  a.pose_controller->target_velocity = a.state.v;
}

bool Scene::has_pose_controller(ActorHandle h) const {
  return articulated(scene_data(handle_), h, "has_articulated_pose_controller").pose_controller.has_value();
}

void Scene::remove_pose_controller(ActorHandle h) {
  SceneData& s = scene_data(handle_);
  Articulation& a = articulated(s, h, "remove_articulated_pose_controller");
  for (const PoseConstraintInfo& info : controller(a, "remove_articulated_pose_controller").info) s.constraints.erase(info.handle);
  a.pose_controller.reset();
}

void Scene::set_pose_controller_params(ActorHandle h, const PoseControllerParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "set_articulated_pose_controller_params";
  Articulation& a = articulated(s, h, what.c_str());
  const PoseController& pc = controller(a, what.c_str());
  check_params(p, a.model.num_links, what);
  for (const PoseConstraintInfo& info : pc.info) {
    ConstraintRecord& c = s.constraints.at(info.handle);
    const PoseTrackingParams t = tracking_of(slice_of(p, info.type), info.link);
    c.stiffness = t.stiffness, c.damping = t.damping, c.saturation = t.saturation;
  }
}

PoseControllerParams Scene::pose_controller_params(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  Articulation& a = articulated(s, h, "get_articulated_pose_controller_params");
  const PoseController& pc = controller(a, "get_articulated_pose_controller_params");
  PoseControllerParams out(a.model.num_links);
  for (const PoseConstraintInfo& info : pc.info) {
    const ConstraintRecord& c = s.constraints.at(info.handle);
    const PoseTrackingParams t{c.stiffness, c.damping, c.saturation};
    if (info.type == PoseConstraintType::LinkTranslation) out.link_pos_tracking[info.link] = t;
    if (info.type == PoseConstraintType::LinkRotation) out.link_rot_tracking[info.link] = t;
    if (info.type == PoseConstraintType::Joint) out.joint_tracking[info.link] = t;
  }
  return out;
}

std::vector<PoseConstraintInfo> Scene::pose_constraints(ActorHandle h) const {
  Articulation& a = articulated(scene_data(handle_), h, "get_articulated_pose_constraints");
  return controller(a, "get_articulated_pose_constraints").info;
}

namespace {

// A joint target, at rest or moving over the next step.
void aim_at_pose(SceneData& s, ActorHandle h, const VecX& pose, bool at_rest, const char* what) {
  Articulation& a = articulated(s, h, what);
  controller(a, what);
  check_pose(a, pose, what, "pose");
  set_pose_target(s, a, pose);
  if (at_rest) a.pose_controller->target_velocity = VecX::Zero(a.model.nv);
}

// A link target, at rest or moving over the next step.
void aim_at_links(SceneData& s, ActorHandle h, std::span<const TransformRT> X_WL, bool at_rest, const char* what) {
  Articulation& a = articulated(s, h, what);
  controller(a, what);
  check_links(a, X_WL, what);
  set_link_target(s, a, X_WL);
  if (at_rest) a.pose_controller->target_velocity = VecX::Zero(a.model.nv);
}

}  // namespace

void Scene::set_target_pose(ActorHandle h, const VecX& pose) {
  aim_at_pose(scene_data(handle_), h, pose, false, "set_articulated_target_pose");
}

void Scene::reset_target_pose(ActorHandle h, const VecX& pose) {
  aim_at_pose(scene_data(handle_), h, pose, true, "reset_articulated_target_pose");
}

void Scene::set_target_link_transforms(ActorHandle h, std::span<const TransformRT> X_WL) {
  aim_at_links(scene_data(handle_), h, X_WL, false, "set_articulated_target_link_transforms");
}

void Scene::reset_target_link_transforms(ActorHandle h, std::span<const TransformRT> X_WL) {
  aim_at_links(scene_data(handle_), h, X_WL, true, "reset_articulated_target_link_transforms");
}

void Scene::set_target_velocity(ActorHandle h, const VecX& velocity) {
  const char* what = "set_articulated_target_velocity";
  Articulation& a = articulated(scene_data(handle_), h, what);
  PoseController& pc = controller(a, what);
  check_pose(a, velocity, what, "velocity");
  pc.target_velocity = velocity;
}

VecX Scene::target_pose(ActorHandle h) const {
  Articulation& a = articulated(scene_data(handle_), h, "get_articulated_target_pose");
  return controller(a, "get_articulated_target_pose").target_pose;
}

std::vector<Transform> Scene::target_link_transforms(ActorHandle h) const {
  Articulation& a = articulated(scene_data(handle_), h, "get_articulated_target_link_transforms");
  return controller(a, "get_articulated_target_link_transforms").target_links;
}

VecX Scene::controller_force(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  const char* what = "get_articulated_controller_force";
  Articulation& a = articulated(s, h, what);
  const PoseController& pc = controller(a, what);
  require_query(s, h, QueryType::ArticulatedControllerForce, what);
  VecX out = VecX::Zero(a.model.nv);
  MatXR J;
  for (const PoseConstraintInfo& info : pc.info) {
    const ConstraintRecord& c = s.constraints.at(info.handle);
    if (c.force.empty()) continue;
    if (info.type == PoseConstraintType::Joint) {
      const std::vector<int> dofs = physics::constraint_dof_indices(c, 0);
      for (size_t k = 0; k < dofs.size(); ++k) out[dofs[k]] += c.force[k];
      continue;
    }
    // a link's force (N) and torque about its centre of mass (N m), world: J_WL^T with the
    // torque moved to the link origin
    link_jacobian_world(a.model, a.kin, info.link, J);
    const SpatialTransform& X = a.kin.X_WL[info.link];
    const Vec3 r = X.R * a.model.inertia[info.link].com;
    const Vec3 f = info.type == PoseConstraintType::LinkTranslation ? Vec3(c.force[0], c.force[1], c.force[2]) : Vec3::Zero();
    const int t = info.type == PoseConstraintType::LinkTranslation ? 3 : 0;
    const Vec3 tau = Vec3(c.force[t], c.force[t + 1], c.force[t + 2]) + r.cross(f);
    out.noalias() += J.topRows<3>().transpose() * f + J.bottomRows<3>().transpose() * tau;
  }
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
