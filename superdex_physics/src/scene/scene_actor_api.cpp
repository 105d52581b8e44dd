// Scene methods that read and write one actor: poses, velocities, forces, articulation queries.

#include <cstdint>
#include <cmath>
#include <utility>

#include "multibody/dynamics.h"
#include "multibody/kinematics.h"
#include "scene/actor_lookup.h"
#include "scene/scene_data.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

Transform to_transform(const SpatialTransform& X) { return {Quat(X.R).normalized(), X.p}; }

void check_size(const char* what, const char* arg, Eigen::Index got, Eigen::Index expected) {
  if (got != expected)
    throw Error(std::string(what) + ": " + arg + " must have " + std::to_string(expected) + " values, got " + std::to_string(got));
}

void check_finite(const char* what, const char* arg, const VecX& x) {
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i])) throw Error(std::string(what) + ": " + arg + "[" + std::to_string(i) + "] is not finite (NaN or infinity)");
}

// True when a free root's joint position is the actor's root pose itself: the base and the joint
// placement are the identity. The pose is then read and written as the joint's quaternion and
// translation, so that a pose set is the pose read back, bit for bit.
bool root_pose_is_joint_position(const Articulation& a) {
  const JointModel& root = a.model.joints[0];
  const SpatialTransform X_WJ = a.state.X_W_base * root.X_PJ;
  return root.type == JointType::Free && X_WJ.R == Mat3::Identity() && X_WJ.p.isZero(0) && root.p_JL.isZero(0);
}

}  // namespace

ActorType Scene::actor_type(ActorHandle h) const {
  ActorRef r = lookup(scene_data(handle_), h, "get_type");
  if (r.soft) return r.soft->model.rod ? ActorType::Rod : ActorType::Soft;
  if (r.articulation->is_rigid || r.link >= 0) return ActorType::Rigid;
  return ActorType::Articulated;
}

bool Scene::is_nested_link_actor(ActorHandle h) const {
  ActorRef r = lookup(scene_data(handle_), h, "is_nested_link_actor");
  return !r.soft && r.link >= 0 && !r.articulation->is_rigid;
}

std::string Scene::actor_name(ActorHandle h) const {
  ActorRef r = lookup(scene_data(handle_), h, "get_name");
  if (r.soft) return r.soft->model.name;
  if (r.link < 0 || r.articulation->is_rigid) return r.articulation->model.name;
  // a link actor: "<articulation>/<link>"
  const std::string& owner = r.articulation->model.name;
  return (owner.empty() ? std::string("unnamed_articulation") : owner) + "/" + r.articulation->model.link_names[r.link];
}

Transform Scene::root_transform(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  if (ActorRef r = lookup(s, h, "get_root_transform"); r.soft) return r.soft->X_WL;
  auto [a, link] = link_of(s, h, "get_root_transform");
  if (link == 0 && root_pose_is_joint_position(*a)) {
    const int o = a->model.joints[0].q_offset;
    return {Quat(a->state.q.segment<4>(o + 3)), a->state.q.segment<3>(o)};
  }
  return to_transform(a->kin.X_WL[link]);
}

void Scene::set_root_transform(ActorHandle h, const Transform& X_WL_in) {
  SceneData& s = scene_data(handle_);
  if (!X_WL_in.translation.allFinite() || !X_WL_in.rotation.coeffs().allFinite() || X_WL_in.rotation.norm() < real(1e-6))
    throw Error("set_root_transform: the transform must be finite with a non-zero quaternion");
  const Transform X_WL{unit_quaternion(X_WL_in.rotation), X_WL_in.translation};
  if (ActorRef r = lookup(s, h, "set_root_transform"); r.soft) {
    // the whole body moves rigidly with its frame; its velocities are unchanged
    SoftBody& b = *r.soft;
    const Transform X_new_old = compose(X_WL, b.X_WL.inverse());
    for (Eigen::Index i = 0; i + 2 < b.state.x.size(); i += 3) b.state.x.segment<3>(i) = X_new_old * Vec3(b.state.x.segment<3>(i));
    for (Eigen::Index i = 0; i + 2 < b.model.pin_target.size(); i += 3)
      b.model.pin_target.segment<3>(i) = X_new_old * Vec3(b.model.pin_target.segment<3>(i));
    b.X_WL = X_WL;
    return;
  }
  Articulation& a = whole(s, h, "set_root_transform");
  const JointModel& root = a.model.joints[0];
  const SpatialTransform X = SpatialTransform::from(X_WL);
  if (root_pose_is_joint_position(a)) {
    a.state.q.segment<3>(root.q_offset) = X_WL.translation;
    a.state.q.segment<4>(root.q_offset + 3) = X_WL.rotation.coeffs();
  } else if (root.type == JointType::Free) {
    // X_WL = X_W_base * X_PJ * X_J(q): solve for the free joint's position
    const SpatialTransform X_J = (a.state.X_W_base * root.X_PJ).inverse() * X * SpatialTransform{Mat3::Identity(), -root.p_JL};
    const Quat q(X_J.R);
    a.state.q.segment<3>(root.q_offset) = X_J.p;
    a.state.q.segment<4>(root.q_offset + 3) = q.normalized().coeffs();
  } else {
    a.state.X_W_base = X * root.X_PJ.inverse();
  }
  refresh_kinematics(a);
}

void Scene::set_velocity(ActorHandle h, const Vec3& v_W, const Vec3& w_W) {
  SceneData& s = scene_data(handle_);
  if (!v_W.allFinite() || !w_W.allFinite()) throw Error("set_velocity: linear and angular velocity must be finite");
  if (ActorRef r = lookup(s, h, "set_velocity"); r.soft) {
    if (!w_W.isZero(0)) throw Error("set_velocity: a soft actor takes a linear velocity only (angular_vel must be zero)");
    for (Eigen::Index i = 0; i + 2 < r.soft->state.v.size(); i += 3) r.soft->state.v.segment<3>(i) = v_W;
    return;
  }
  Articulation& a = whole(s, h, "set_velocity");
  if (a.model.joints[0].type != JointType::Free)
    throw Error("set_velocity: " + describe(h) + " ('" + a.model.name + "') has no free root: it is static or welded");
  // v_W is the centre of mass's velocity: the origin's is v_W - w x (com - origin); linear
  // velocity in the free joint's parent frame, angular velocity in the body frame
  const Mat3 R_WP = (a.state.X_W_base * a.model.joints[0].X_PJ).R;
  const Vec3 r_W = a.kin.X_WL[0].R * a.model.inertia[0].com;
  // and the joint origin's, the link origin's minus w x p_JL (the link moves with the joint's axes)
  const Vec3 p_JL_W = a.kin.X_WL[0].R * a.model.joints[0].p_JL;
  a.state.v.segment<3>(0) = R_WP.transpose() * (v_W - w_W.cross(r_W) - w_W.cross(p_JL_W));
  a.state.v.segment<3>(3) = a.kin.X_WL[0].R.transpose() * w_W;
  refresh_kinematics(a);
}

Vec6 Scene::velocity(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  Vec6 out;
  if (ActorRef r = lookup(s, h, "get_velocity"); r.soft) {
    // the rigid motion of the nodes: momentum over mass, and the angular momentum about the
    // centre of mass through the inertia there
    const SoftBody& b = *r.soft;
    const int n = static_cast<int>(b.model.node_mass.size());
    Vec3 c = Vec3::Zero(), p = Vec3::Zero();
    for (int i = 0; i < n; ++i) c += b.model.node_mass[i] * b.state.x.segment<3>(3 * i), p += b.model.node_mass[i] * b.state.v.segment<3>(3 * i);
    c /= b.model.total_mass;
    const Vec3 v = p / b.model.total_mass;
    Vec3 L = Vec3::Zero();
    Mat3 I = Mat3::Zero();
    for (int i = 0; i < n; ++i) {
      const Vec3 d = b.state.x.segment<3>(3 * i) - c;
      L += b.model.node_mass[i] * d.cross(b.state.v.segment<3>(3 * i) - v);
      I += b.model.node_mass[i] * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
    }
    out.head<3>() = v;
    out.tail<3>() = I.determinant() > 0 ? Vec3(I.ldlt().solve(L)) : Vec3::Zero();
    return out;
  }
  auto [a, link] = link_of(s, h, "get_velocity");
  const Mat3& R = a->kin.X_WL[link].R;
  // the centre of mass's velocity, and the angular velocity (world)
  const Vec3 w_W = R * a->kin.V_L[link].tail<3>();
  out.head<3>() = R * a->kin.V_L[link].head<3>() + w_W.cross(R * a->model.inertia[link].com);
  out.tail<3>() = w_W;
  return out;
}

real Scene::mass(ActorHandle h) const {
  ActorRef r = lookup(scene_data(handle_), h, "get_mass");
  if (r.soft) return r.soft->model.total_mass;
  if (r.link >= 0) return r.articulation->model.inertia[r.link].mass;
  real m = 0;
  for (const auto& I : r.articulation->model.inertia) m += I.mass;
  return m;
}

int Scene::num_dofs(ActorHandle h) const {
  ActorRef r = lookup(scene_data(handle_), h, "get_num_dofs");
  return r.soft ? static_cast<int>(r.soft->state.v.size()) : r.articulation->model.nv;
}

void Scene::set_external_forces_on_dofs(ActorHandle h, std::span<const int> dofs, std::span<const real> values) {
  const char* what = "set_external_forces_on_dofs";
  SceneData& s = scene_data(handle_);
  ActorRef ref = lookup(s, h, what);
  Articulation* articulation = ref.soft ? nullptr : &whole(s, h, what);
  VecX& target = ref.soft ? ref.soft->state.tau_external : articulation->state.tau_external;
  const int nv = ref.soft ? static_cast<int>(target.size()) : articulation->model.nv;
  if (dofs.size() != values.size())
    throw Error(std::string(what) + ": dof_indices has " + std::to_string(dofs.size()) + " entries but force_values has " +
                std::to_string(values.size()));
  // every entry is checked before anything changes; a repeated DOF is found by a bit mask (a
  // list when the actor has more than 64 DOFs)
  std::uint64_t seen_mask = 0;
  std::vector<char> seen(nv > 64 ? nv : 0, 0);
  for (size_t i = 0; i < dofs.size(); ++i) {
    const int d = dofs[i];
    if (d < 0 || d >= nv)
      throw Error(std::string(what) + ": dof_indices[" + std::to_string(i) + "] = " + std::to_string(d) +
                  " is out of range: the actor has " + std::to_string(nv) + " DOFs");
    const bool repeated = nv > 64 ? std::exchange(seen[d], 1) != 0 : (seen_mask >> d) & 1;
    seen_mask |= nv > 64 ? 0 : std::uint64_t(1) << d;
    if (repeated)
      throw Error(std::string(what) + ": dof_indices[" + std::to_string(i) + "] = " + std::to_string(d) + " appears twice");
    if (!std::isfinite(values[i]))
      throw Error(std::string(what) + ": force_values[" + std::to_string(i) + "] is not finite (NaN or infinity)");
  }
  target.setZero(nv);
  for (size_t i = 0; i < dofs.size(); ++i) target[dofs[i]] = values[i];
}

void Scene::clear_external_forces(ActorHandle h) {
  ActorRef r = lookup(scene_data(handle_), h, "clear_external_forces");
  if (r.soft) {
    r.soft->state.tau_external.setZero();
    return;
  }
  whole(scene_data(handle_), h, "clear_external_forces").state.tau_external.setZero();
}

VecX Scene::external_forces(ActorHandle h) const {
  ActorRef r = lookup(scene_data(handle_), h, "get_external_forces");
  if (r.soft) return r.soft->state.tau_external;
  return whole(scene_data(handle_), h, "get_external_forces").state.tau_external;
}

std::vector<ActorHandle> Scene::nested_link_actors(ActorHandle h) const {
  Articulation& a = whole(scene_data(handle_), h, "get_nested_link_actors");
  if (a.is_rigid) throw Error("get_nested_link_actors: " + describe(h) + " is a rigid actor, not an articulation");
  return a.link_handles;
}

std::vector<ActorHandle> Scene::nested_soft_actors(ActorHandle h) const {
  Articulation& a = whole(scene_data(handle_), h, "get_nested_soft_actors");
  if (a.is_rigid) throw Error("get_nested_soft_actors: " + describe(h) + " is a rigid actor, not an articulation");
  return a.nested_softs;
}

bool Scene::is_nested_soft_actor(ActorHandle h) const {
  const ActorRef r = lookup(scene_data(handle_), h, "is_nested_soft_actor");
  return r.soft && r.soft->skeleton.is_valid();
}

ActorHandle Scene::articulated_actor_of_link(ActorHandle h) const {
  ActorRef r = lookup(scene_data(handle_), h, "get_articulated_actor");
  if (!is_link_actor(r)) throw Error("get_articulated_actor: " + describe(h) + " is not a link actor");
  return r.articulation->handle;
}

int Scene::link_index(ActorHandle h) const {
  ActorRef r = lookup(scene_data(handle_), h, "get_link_index");
  if (!is_link_actor(r)) throw Error("get_link_index: " + describe(h) + " is not a link actor");
  return r.link;
}

ArticulatedShapeInfo Scene::articulated_shape_info(ActorHandle h) const {
  const Articulation& a = whole(scene_data(handle_), h, "get_articulated_shape_info");
  ArticulatedShapeInfo info;
  info.link_names = a.model.link_names;
  info.joint_names = a.model.joint_names;
  info.parents = a.model.parent;
  const real inf = std::numeric_limits<real>::infinity();
  for (int i = 0; i < a.model.num_links; ++i) {
    const JointModel& j = a.model.joints[i];
    const JointDesc& jd = a.model.desc.joints[i];
    info.joint_types.push_back(j.type);
    info.joint_axes.push_back(j.axis);
    ArticulatedDofInfo d;
    d.offset = j.v_offset;
    switch (j.type) {
      case JointType::Prismatic: d.trans_size = 1; break;
      case JointType::Revolute: d.rot_size = 1; break;
      case JointType::Spherical: d.rot_size = 3; break;
      case JointType::Free: d.trans_size = 3, d.rot_size = 3; break;
      default: break;
    }
    info.dof_info.push_back(d);
    // at rest the link frame is its joint frame moved by joint_from_link; root-from-link
    // composes parent-from-joint and joint-from-link down the tree
    Transform X_PJ = jd.parent_link_from_joint;
    X_PJ.rotation.normalize();
    info.parent_link_from_joint.push_back(X_PJ);
    info.joint_from_child_link.push_back(Transform{Quaternion::Identity(), a.model.desc.links[i].joint_from_link});
    info.joint_min_limits.push_back(j.has_lower ? Real3(j.lower * j.axis) : Real3::Constant(-inf));
    info.joint_max_limits.push_back(j.has_upper ? Real3(j.upper * j.axis) : Real3::Constant(inf));
  }
  info.root_from_links_at_rest.resize(a.model.num_links);
  for (int i : a.model.order) {
    const int parent = a.model.parent[i];
    const Transform X_PL = compose(info.parent_link_from_joint[i], info.joint_from_child_link[i]);
    info.root_from_links_at_rest[i] = parent < 0 ? X_PL : compose(info.root_from_links_at_rest[parent], X_PL);
  }
  return info;
}

std::vector<Transform> Scene::link_transforms(ActorHandle h) const {
  const Articulation& a = whole(scene_data(handle_), h, "get_articulated_link_transforms");
  std::vector<Transform> out;
  out.reserve(a.kin.X_WL.size());
  for (const auto& X : a.kin.X_WL) out.push_back(to_transform(X));
  return out;
}

Transform Scene::link_transform(ActorHandle h, int link) const {
  const Articulation& a = whole(scene_data(handle_), h, "link_transform");
  if (link < 0 || link >= static_cast<int>(a.kin.X_WL.size()))
    throw Error("link_transform: link " + std::to_string(link) + " is out of range (the articulation has " +
                std::to_string(a.kin.X_WL.size()) + " links)");
  return to_transform(a.kin.X_WL[link]);
}

VecX Scene::pose(ActorHandle h) const {
  VecX out;
  pose(h, out);
  return out;
}

void Scene::pose(ActorHandle h, VecX& out) const {
  const Articulation& a = whole(scene_data(handle_), h, "get_articulated_pose");
  out.resize(a.model.nv);
  pose_from_q(a.model, a.state.q, out.data());
}

void Scene::set_pose(ActorHandle h, const VecX& pose) {
  const char* what = "set_articulated_pose_from_joints";
  Articulation& a = whole(scene_data(handle_), h, what);
  check_size(what, "pose", pose.size(), a.model.nv);
  check_finite(what, "pose", pose);
  q_from_pose(a.model, pose.data(), false, a.state.q);
  refresh_kinematics(a);
  // a pose controller's target jumps there too, at rest
  if (a.pose_controller) reset_target_pose(h, pose);
}

VecX Scene::joint_velocities(ActorHandle h) const { return whole(scene_data(handle_), h, "get_articulated_joint_velocities").state.v; }

void Scene::joint_velocities(ActorHandle h, VecX& out) const {
  out = whole(scene_data(handle_), h, "get_articulated_joint_velocities").state.v;
}

void Scene::set_joint_velocities(ActorHandle h, const VecX& v) {
  const char* what = "set_articulated_joint_velocities";
  Articulation& a = whole(scene_data(handle_), h, what);
  check_size(what, "velocities", v.size(), a.model.nv);
  check_finite(what, "velocities", v);
  a.state.v = v;
  refresh_kinematics(a);
}

void Scene::set_joint_drive(ActorHandle h, int dof, const JointDrive& d) {
  const char* what = "set_joint_drive";
  Articulation& a = whole(scene_data(handle_), h, what);
  if (dof < 0 || dof >= a.model.nv)
    throw Error(std::string(what) + ": dof " + std::to_string(dof) + " is out of range: the actor has " + std::to_string(a.model.nv) + " DOFs");
  const JointModel* joint = nullptr;
  for (const JointModel& j : a.model.joints)
    if (dof >= j.v_offset && dof < j.v_offset + j.nv) joint = &j;
  if (joint->type != JointType::Revolute && joint->type != JointType::Prismatic)
    throw Error(std::string(what) + ": dof " + std::to_string(dof) + " belongs to a " + joint_type_name(joint->type) +
                " joint; drives act on revolute and prismatic joints");
  for (real x : {d.stiffness, d.damping, d.target_position, d.target_velocity, d.max_effort})
    if (!std::isfinite(x)) throw Error(std::string(what) + ": the drive's values must be finite");
  if (d.stiffness < 0 || d.damping < 0) throw Error(std::string(what) + ": stiffness and damping must be >= 0");
  a.state.drives[dof] = d;
}

void Scene::clear_joint_drives(ActorHandle h) {
  Articulation& a = whole(scene_data(handle_), h, "clear_joint_drives");
  a.state.drives.assign(a.model.nv, JointDrive{});
  a.state.link_drives.assign(a.model.num_links, LinkDrive{});
}

void Scene::set_link_drive(ActorHandle h, const LinkDrive& d) {
  const char* what = "set_link_drive";
  auto [a, link] = link_of(scene_data(handle_), h, what);
  if (a->model.nv == 0) throw Error(std::string(what) + ": " + describe(h) + " cannot move (it has no DOFs)");
  for (real x : {d.linear_stiffness, d.linear_damping, d.angular_stiffness, d.angular_damping})
    if (!std::isfinite(x) || x < 0) throw Error(std::string(what) + ": stiffness and damping must be finite and >= 0");
  if (!std::isfinite(d.max_force) || !std::isfinite(d.max_torque)) throw Error(std::string(what) + ": limits must be finite");
  if (!d.target.translation.allFinite() || !d.target.rotation.coeffs().allFinite() || d.target.rotation.norm() < real(1e-6) ||
      !d.target_linear_velocity.allFinite() || !d.target_angular_velocity.allFinite())
    throw Error(std::string(what) + ": the target must be finite with a non-zero quaternion");
  LinkDrive drive = d;
  drive.target.rotation.normalize();
  a->state.link_drives[link] = drive;
}

VecX Scene::joint_drive_efforts(ActorHandle h) const {
  const Articulation& a = whole(scene_data(handle_), h, "get_joint_drive_efforts");
  return a.drive_efforts.size() == a.model.nv ? a.drive_efforts : VecX::Zero(a.model.nv);
}

MatXR Scene::link_jacobian(ActorHandle h) const {
  MatXR J;
  link_jacobian(h, J);
  return J;
}

void Scene::link_jacobian(ActorHandle h, MatXR& J_WL) const {
  auto [a, link] = link_of(scene_data(handle_), h, "get_articulated_jacobian");
  link_jacobian_world(a->model, a->kin, link, J_WL);
}

MatX Scene::mass_matrix(ActorHandle h) const {
  const Articulation& a = whole(scene_data(handle_), h, "get_articulated_mass_matrix");
  return physics::mass_matrix(a.model, a.kin);
}

VecX Scene::bias_forces(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  const Articulation& a = whole(s, h, "get_articulated_bias_forces");
  return physics::bias_forces(a.model, a.state, a.kin, s.gravity);
}

VecX Scene::forward_dynamics(ActorHandle h, const VecX& tau) const {
  const char* what = "compute_articulated_forward_dynamics";
  SceneData& s = scene_data(handle_);
  const Articulation& a = whole(s, h, what);
  check_size(what, "tau", tau.size(), a.model.nv);
  check_finite(what, "tau", tau);
  const MatX M = physics::mass_matrix(a.model, a.kin);
  return M.llt().solve(tau - physics::bias_forces(a.model, a.state, a.kin, s.gravity));
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
