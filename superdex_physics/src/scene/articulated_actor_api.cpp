// Articulations: joint friction and armature, DOF limits, poses from link transforms, and the
// joint-aware arithmetic of poses (rotation vectors composed as rotations).

#include <cmath>

#include "multibody/kinematics.h"
#include "scene/articulation_poses.h"
#include "scene/actor_lookup.h"
#include "superdex/physics/log.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

Quat rotation_of(const Vec3& r) {
  const real angle = r.norm();
  return angle > 0 ? Quat(Eigen::AngleAxis<real>(angle, r / angle)) : Quat::Identity();
}

Vec3 rotation_vector(const Quat& q) {
  const Eigen::AngleAxis<real> aa(q.normalized());
  return aa.angle() * aa.axis();
}

void check_pose_size(const char* what, const char* arg, const VecX& v, int nv) {
  if (v.size() != nv)
    throw Error(std::string(what) + ": " + arg + " must hold one value per DOF (" + std::to_string(nv) + "), got " + std::to_string(v.size()));
}

}  // namespace

std::vector<ArticulatedJointFrictionParams> Scene::joint_friction_params(ActorHandle h) const {
  return articulated(scene_data(handle_), h, "get_articulated_joint_friction_params").joint_friction;
}

void Scene::set_joint_friction_params(ActorHandle h, const std::vector<ArticulatedJointFrictionParams>& friction) {
  const char* what = "set_articulated_joint_friction_params";
  Articulation& a = articulated(scene_data(handle_), h, what);
  if (static_cast<int>(friction.size()) != a.model.num_links)
    throw Error(std::string(what) + ": friction must hold one entry per joint (" + std::to_string(a.model.num_links) + "), got " +
                std::to_string(friction.size()));
  for (size_t i = 0; i < friction.size(); ++i) validate(friction[i], std::string(what) + ": friction[" + std::to_string(i) + "]");
  for (size_t i = 0; i < friction.size(); ++i) {
    // dry friction is exact (a bounded row of the convex problem): the regularisation below
    // falloff_vel is not needed, and stiction beyond it is not modelled
    if (friction[i].stiction_extra > 0)
      log_warning(std::string(what) + ": friction[" + std::to_string(i) + "].stiction_extra is not modelled by this engine; Coulomb friction " +
                  "acts alone");
    a.model.joints[i].coulomb = friction[i].coulomb;
    a.model.joints[i].viscous = friction[i].viscous;
  }
  a.joint_friction = friction;
}

std::vector<real> Scene::joint_inertia_params(ActorHandle h) const {
  const Articulation& a = articulated(scene_data(handle_), h, "get_articulated_joint_inertia_params");
  std::vector<real> out;
  for (const JointModel& j : a.model.joints) out.push_back(j.armature);
  return out;
}

void Scene::set_joint_inertia_params(ActorHandle h, std::span<const real> inertia) {
  const char* what = "set_articulated_joint_inertia_params";
  Articulation& a = articulated(scene_data(handle_), h, what);
  if (static_cast<int>(inertia.size()) != a.model.num_links)
    throw Error(std::string(what) + ": inertia must hold one value per joint (" + std::to_string(a.model.num_links) + "), got " +
                std::to_string(inertia.size()));
  for (size_t i = 0; i < inertia.size(); ++i)
    if (!(std::isfinite(inertia[i]) && inertia[i] >= 0))
      throw Error(std::string(what) + ": inertia[" + std::to_string(i) + "] must be a finite number >= 0, got " + std::to_string(inertia[i]));
  for (size_t i = 0; i < inertia.size(); ++i) a.model.joints[i].armature = inertia[i];
}

std::vector<Real2> Scene::dof_limits(ActorHandle h) const {
  const Articulation& a = articulated(scene_data(handle_), h, "get_articulated_dof_limits");
  const real inf = std::numeric_limits<real>::infinity();
  std::vector<Real2> out(a.model.nv, Real2(-inf, inf));
  for (const JointModel& j : a.model.joints)
    if (j.nv == 1) out[j.v_offset] = Real2(j.has_lower ? j.lower : -inf, j.has_upper ? j.upper : inf);
  return out;
}

VecX pose_from_link_frames(const Articulation& a, std::span<const TransformRT> X_WL) {
  const ArticulationModel& m = a.model;
  VecX pose(m.nv);
  for (int i = 0; i < m.num_links; ++i) {
    const JointModel& j = m.joints[i];
    const int p = m.parent[i];
    const SpatialTransform X_WP = p < 0 ? a.state.X_W_base : SpatialTransform::from(Transform{X_WL[p].rotation.normalized(), X_WL[p].translation});
    const SpatialTransform X_W_child = SpatialTransform::from(Transform{X_WL[i].rotation.normalized(), X_WL[i].translation});
    const SpatialTransform X_J = (X_WP * j.X_PJ).inverse() * X_W_child * SpatialTransform{Mat3::Identity(), -j.p_JL};
    switch (j.type) {
      case JointType::Revolute: pose[j.v_offset] = rotation_vector(Quat(X_J.R)).dot(j.axis); break;
      case JointType::Prismatic: pose[j.v_offset] = X_J.p.dot(j.axis); break;
      case JointType::Spherical: pose.segment<3>(j.v_offset) = rotation_vector(Quat(X_J.R)); break;
      case JointType::Free:
        pose.segment<3>(j.v_offset) = X_J.p;
        pose.segment<3>(j.v_offset + 3) = rotation_vector(Quat(X_J.R));
        break;
      default: break;
    }
  }
  return pose;
}

VecX pose_plus_delta(const ArticulationModel& m, const VecX& pose, const VecX& delta) {
  VecX out = pose + delta;
  for (const JointModel& j : m.joints) {
    // a 3-D rotation's delta is an increment of its rotation in the child frame (where its
    // velocity lives): exp(pose) exp(delta)
    const int r = j.type == JointType::Spherical ? j.v_offset : j.type == JointType::Free ? j.v_offset + 3 : -1;
    if (r < 0) continue;
    out.segment<3>(r) = rotation_vector(rotation_of(pose.segment<3>(r)) * rotation_of(delta.segment<3>(r)));
  }
  return out;
}

std::vector<Transform> link_frames_at(const Articulation& a, const VecX& pose) {
  VecX q = a.state.q;
  q_from_pose(a.model, pose.data(), false, q);
  ArticulationKinematics kin;
  update_kinematics(a.model, q, VecX::Zero(a.model.nv), a.state.X_W_base, kin);
  std::vector<Transform> out;
  out.reserve(kin.X_WL.size());
  for (const SpatialTransform& X : kin.X_WL) out.push_back({Quat(X.R).normalized(), X.p});
  return out;
}

void Scene::set_pose_from_links(ActorHandle h, std::span<const TransformRT> X_WL) {
  const char* what = "set_articulated_pose_from_links";
  Articulation& a = articulated(scene_data(handle_), h, what);
  if (static_cast<int>(X_WL.size()) != a.model.num_links)
    throw Error(std::string(what) + ": world_from_links must hold one transform per link (" + std::to_string(a.model.num_links) + "), got " +
                std::to_string(X_WL.size()));
  set_pose(h, pose_from_link_frames(a, X_WL));
}

VecX Scene::add_delta_to_pose(ActorHandle h, const VecX& pose, const VecX& delta) const {
  const char* what = "add_articulated_delta_to_pose";
  const Articulation& a = articulated(scene_data(handle_), h, what);
  check_pose_size(what, "pose", pose, a.model.nv);
  check_pose_size(what, "delta_dofs", delta, a.model.nv);
  return pose_plus_delta(a.model, pose, delta);
}

VecX Scene::pose_delta(ActorHandle h, const VecX& base, const VecX& target) const {
  const char* what = "compute_articulated_pose_delta";
  const Articulation& a = articulated(scene_data(handle_), h, what);
  check_pose_size(what, "pose_base", base, a.model.nv);
  check_pose_size(what, "pose_target", target, a.model.nv);
  VecX out = target - base;
  for (const JointModel& j : a.model.joints) {
    const int r = j.type == JointType::Spherical ? j.v_offset : j.type == JointType::Free ? j.v_offset + 3 : -1;
    if (r < 0) continue;
    out.segment<3>(r) = rotation_vector(rotation_of(base.segment<3>(r)).inverse() * rotation_of(target.segment<3>(r)));
  }
  return out;
}

void Scene::pose_distance(ActorHandle h, const VecX& pa, const VecX& pb, VecX& translation, VecX& rotation) const {
  const char* what = "get_articulated_pose_distance";
  const Articulation& a = articulated(scene_data(handle_), h, what);
  check_pose_size(what, "pose_a", pa, a.model.nv);
  check_pose_size(what, "pose_b", pb, a.model.nv);
  translation.setZero(a.model.num_links);
  rotation.setZero(a.model.num_links);
  for (int i = 0; i < a.model.num_links; ++i) {
    const JointModel& j = a.model.joints[i];
    switch (j.type) {
      case JointType::Prismatic: translation[i] = std::abs(pa[j.v_offset] - pb[j.v_offset]); break;
      case JointType::Revolute: rotation[i] = std::abs(pa[j.v_offset] - pb[j.v_offset]); break;
      case JointType::Spherical:
        rotation[i] = rotation_of(pa.segment<3>(j.v_offset)).angularDistance(rotation_of(pb.segment<3>(j.v_offset)));
        break;
      case JointType::Free:
        translation[i] = (pa.segment<3>(j.v_offset) - pb.segment<3>(j.v_offset)).norm();
        rotation[i] = rotation_of(pa.segment<3>(j.v_offset + 3)).angularDistance(rotation_of(pb.segment<3>(j.v_offset + 3)));
        break;
      default: break;
    }
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
