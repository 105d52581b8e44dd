// Validation of an ArticulationDesc and construction of its model and initial state.

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "multibody/articulation_model.h"
#include "superdex/physics/inertia.h"
#include "multibody/dynamics.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

const char* joint_type_name(JointType type) { return articulated_joint_type_name(type); }

int joint_num_dofs(JointType type) {
  switch (type) {
    case JointType::Hard: return 0;
    case JointType::Free: return 6;
    case JointType::Revolute:
    case JointType::Prismatic: return 1;
    case JointType::Spherical: return 3;
    default: return 0;
  }
}

namespace {

int joint_num_positions(JointType type) {
  switch (type) {
    case JointType::Free: return 7;
    case JointType::Spherical: return 4;
    default: return joint_num_dofs(type);
  }
}

struct Reporter {
  const std::string& source;
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw Error(source + ": " + path + ": " + what);
  }
};

std::string at(const char* list, size_t i, const char* field = nullptr) {
  std::ostringstream os;
  os << list << "[" << i << "]";
  if (field) os << "." << field;
  return os.str();
}

std::string num(real x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

void check_transform(const Transform& X, const Reporter& r, const std::string& path) {
  if (!X.translation.allFinite()) r.fail(path + ".translation", "must be finite");
  if (!X.rotation.coeffs().allFinite() || X.rotation.norm() < real(1e-6))
    r.fail(path + ".rotation", "must be a finite, non-zero quaternion [x, y, z, w]");
}

// Checks a rotational inertia: symmetric positive definite and satisfying the triangle
// inequality of principal moments (a physical mass distribution).
void check_inertia(const Mat3& I, const Reporter& r, const std::string& path) {
  if (auto defect = inertia_defect(I)) r.fail(path, *defect);
}

void check_nonnegative(real x, const Reporter& r, const std::string& path) {
  if (!std::isfinite(x) || x < 0) r.fail(path, "must be a finite number >= 0, got " + num(x));
}

// fixedTendons[k] on the model's revolute and prismatic joints, checked field by field
ArticulationModel::Tendon tendon_model(const FixedTendon& t, const ArticulationModel& m, const Reporter& r, size_t k) {
  const std::string path = at("fixedTendons", k);
  if (t.joints.empty()) r.fail(path + ".joints", "a tendon needs at least one joint");
  if (t.coefficients.size() != t.joints.size())
    r.fail(path + ".coefficients", "expected one per joint (" + std::to_string(t.joints.size()) + "), got " + std::to_string(t.coefficients.size()));
  ArticulationModel::Tendon out;
  for (size_t j = 0; j < t.joints.size(); ++j) {
    const auto it = std::find(m.joint_names.begin(), m.joint_names.end(), t.joints[j]);
    const std::string jpath = path + ".joints[" + std::to_string(j) + "]";
    if (it == m.joint_names.end()) r.fail(jpath, "no joint named '" + t.joints[j] + "'");
    const JointModel& joint = m.joints[static_cast<size_t>(it - m.joint_names.begin())];
    if (joint.type != JointType::Revolute && joint.type != JointType::Prismatic)
      r.fail(jpath, "joint '" + t.joints[j] + "' is " + joint_type_name(joint.type) + "; tendons run over revolute and prismatic joints");
    if (!std::isfinite(t.coefficients[j])) r.fail(path + ".coefficients[" + std::to_string(j) + "]", "must be finite");
    out.dofs.push_back(joint.v_offset);
    out.q.push_back(joint.q_offset);
    out.coefficients.push_back(t.coefficients[j]);
  }
  if ((t.has_lower && !std::isfinite(t.lower)) || (t.has_upper && !std::isfinite(t.upper))) r.fail(path + ".range", "must be finite");
  if (t.has_lower && t.has_upper && t.lower > t.upper)
    r.fail(path + ".range", "lower (" + num(t.lower) + ") is above upper (" + num(t.upper) + ")");
  check_nonnegative(t.stiffness, r, path + ".stiffness");
  check_nonnegative(t.damping, r, path + ".damping");
  if (!std::isfinite(t.rest_length)) r.fail(path + ".restLength", "must be finite");
  out.has_lower = t.has_lower;
  out.has_upper = t.has_upper;
  out.lower = t.lower;
  out.upper = t.upper;
  out.stiffness = t.stiffness;
  out.damping = t.damping;
  out.rest_length = t.rest_length;
  return out;
}

}  // namespace

ShapeGeometry scaled_shape(const ShapeGeometry& shape, const Vec3& s, const std::string& where) {
  auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };
  if (!s.allFinite() || (s.array() <= 0).any()) fail("shapeScale must be positive and finite");
  if (auto* sph = std::get_if<SphereShape>(&shape)) {
    if (std::abs(s.x() - s.y()) > real(1e-6) * s.x() || std::abs(s.x() - s.z()) > real(1e-6) * s.x())
      fail("a sphere needs a uniform shapeScale");
    return SphereShape{sph->center.cwiseProduct(s), sph->radius * s.x()};
  }
  if (auto* box = std::get_if<BoxShape>(&shape)) return BoxShape{box->half_extents.cwiseProduct(s)};
  if (auto* cap = std::get_if<CapsuleShape>(&shape)) {
    if (std::abs(s.x() - s.y()) > real(1e-6) * s.x()) fail("a capsule needs shapeScale x == y");
    return CapsuleShape{cap->radius * s.x(), cap->half_length * s.z()};
  }
  return shape;
}

JointCoupling coupling_of(const LinearTransmission& t, const std::vector<JointDesc>& joints, const std::string& where) {
  if (t.joint_indices.size() != 2 || t.joint_coefficients.size() != 2)
    throw Error(where + ".jointIndices: a coupling joins two joints, got " + std::to_string(t.joint_indices.size()));
  for (size_t k = 0; k < 2; ++k)
    if (t.joint_indices[k] < 0 || t.joint_indices[k] >= static_cast<int>(joints.size()))
      throw Error(where + ".jointIndices[" + std::to_string(k) + "]: expected the index of a joint (0 to " + std::to_string(joints.size()) +
                  " - 1), got " + std::to_string(t.joint_indices[k]));
  if (t.joint_coefficients[1] == 0) throw Error(where + ".jointCoefficients[1]: must not be zero (the second joint follows the first)");
  JointCoupling c;
  c.leader = joints[static_cast<size_t>(t.joint_indices[0])].name;
  c.joint = joints[static_cast<size_t>(t.joint_indices[1])].name;
  c.ratio = -t.joint_coefficients[0] / t.joint_coefficients[1];
  c.offset = t.target_displacement / t.joint_coefficients[1];
  return c;
}

ArticulationModel build_articulation_model(const ArticulationDesc& desc, const std::string& source) {
  const Reporter r{source};
  const int n = static_cast<int>(desc.links.size());
  if (n == 0) r.fail("links", "an articulation needs at least one link");
  if (desc.joints.size() != desc.links.size())
    r.fail("joints", "expected exactly one joint per link (" + std::to_string(n) + " links), got " +
                         std::to_string(desc.joints.size()));
  check_transform(desc.world_from_root, r, "worldFromRoot");

  ArticulationModel m;
  m.name = desc.name;
  m.num_links = n;
  m.parent.resize(n);
  m.joints.resize(n);
  m.inertia.resize(n);
  m.has_gravity.resize(n);

  // names unique and non-empty
  std::set<std::string> link_names, joint_names;
  for (int i = 0; i < n; ++i) {
    const auto& L = desc.links[i];
    const auto& J = desc.joints[i];
    if (L.name.empty()) r.fail(at("links", i, "name"), "must be a non-empty string");
    if (!link_names.insert(L.name).second) r.fail(at("links", i, "name"), "duplicate link name '" + L.name + "'");
    if (J.name.empty()) r.fail(at("joints", i, "name"), "must be a non-empty string");
    if (!joint_names.insert(J.name).second) r.fail(at("joints", i, "name"), "duplicate joint name '" + J.name + "'");
    m.link_names.push_back(L.name);
    m.joint_names.push_back(J.name);
  }

  // the link tree: link 0 is the root, every other link has a parent, and there is no cycle
  for (int i = 0; i < n; ++i) {
    const int p = desc.links[i].parent_link;
    if (i == 0) {
      if (p != -1) r.fail(at("links", 0, "parentLink"), "links[0] is the root and must not have a parent");
    } else {
      if (p == -1) r.fail(at("links", i, "parentLink"), "missing: only links[0] may be the root");
      if (p < 0 || p >= n)
        r.fail(at("links", i, "parentLink"), "refers to link " + std::to_string(p) + ", which does not exist (" +
                                                 std::to_string(n) + " links)");
      if (p == i) r.fail(at("links", i, "parentLink"), "a link cannot be its own parent");
    }
    m.parent[i] = p;
  }
  for (int i = 0; i < n; ++i) {
    int k = i, steps = 0;
    while (k != -1 && steps <= n) k = m.parent[k], ++steps;
    if (k != -1) r.fail(at("links", i, "parentLink"), "the link tree has a cycle through link '" + desc.links[i].name + "'");
  }
  // topological order: breadth-first from the root
  std::vector<std::vector<int>> children(n);
  for (int i = 1; i < n; ++i) children[m.parent[i]].push_back(i);
  m.order.push_back(0);
  for (size_t k = 0; k < m.order.size(); ++k)
    for (int c : children[m.order[k]]) m.order.push_back(c);

  // joints
  int q_offset = 0, v_offset = 0;
  for (int i = 0; i < n; ++i) {
    const JointDesc& jd = desc.joints[i];
    JointModel& j = m.joints[i];
    j.type = jd.type;
    if (jd.type == JointType::Cycle || jd.type == JointType::Invalid)
      r.fail(at("joints", i, "type"), std::string("must be Hard, Free, Revolute, Prismatic or Spherical, got ") + joint_type_name(jd.type));
    if (i > 0 && jd.type == JointType::Free)
      r.fail(at("joints", i, "type"), "only the root joint (joints[0]) may be Free");
    check_transform(jd.parent_link_from_joint, r, at("joints", i, "parentLinkFromJoint"));
    Transform X_PJ = jd.parent_link_from_joint;
    X_PJ.rotation.normalize();
    j.X_PJ = SpatialTransform::from(X_PJ);
    const Vec3& p_JL = desc.links[i].joint_from_link;
    if (!p_JL.allFinite()) r.fail(at("links", i, "jointFromLink"), "must be finite");
    // a welded link's offset is constant: part of its joint's placement
    if (jd.type == JointType::Hard || jd.type == JointType::Cycle || jd.type == JointType::Invalid)
      j.X_PJ = j.X_PJ * SpatialTransform{Mat3::Identity(), p_JL};
    else
      j.p_JL = p_JL;
    if (jd.type == JointType::Revolute || jd.type == JointType::Prismatic) {
      if (!jd.axis.allFinite() || jd.axis.norm() < real(1e-9)) r.fail(at("joints", i, "axis"), "must be a finite, non-zero vector");
      j.axis = jd.axis.normalized();
      if (jd.min_limit) {
        if (!jd.min_limit->allFinite()) r.fail(at("joints", i, "minLimit"), "must be finite");
        j.has_lower = true;
        j.lower = j.axis.dot(*jd.min_limit);
      }
      if (jd.max_limit) {
        if (!jd.max_limit->allFinite()) r.fail(at("joints", i, "maxLimit"), "must be finite");
        j.has_upper = true;
        j.upper = j.axis.dot(*jd.max_limit);
      }
      if (j.has_lower && j.has_upper && j.lower > j.upper)
        r.fail(at("joints", i, "minLimit"), "the lower limit " + num(j.lower) + " exceeds the upper limit " + num(j.upper));
    }
    check_nonnegative(jd.coulomb_friction, r, at("joints", i, "friction.coulomb"));
    check_nonnegative(jd.viscous_friction, r, at("joints", i, "friction.viscous"));
    check_nonnegative(jd.armature, r, at("joints", i, "inertia"));
    check_nonnegative(jd.limit_stiffness, r, at("joints", i, "limitStiffness"));
    check_nonnegative(jd.limit_damping, r, at("joints", i, "limitDamping"));
    if (!std::isfinite(jd.effort_limit)) r.fail(at("joints", i, "effortLimit"), "must be finite");
    j.coulomb = jd.coulomb_friction;
    j.viscous = jd.viscous_friction;
    j.armature = jd.armature;
    j.limit_stiffness = jd.limit_stiffness;
    j.limit_damping = jd.limit_damping;
    j.effort_limit = jd.effort_limit;
    j.nq = joint_num_positions(jd.type);
    j.nv = joint_num_dofs(jd.type);
    j.q_offset = q_offset;
    j.v_offset = v_offset;
    q_offset += j.nq;
    v_offset += j.nv;
    switch (jd.type) {
      case JointType::Revolute: j.S.col(0).tail<3>() = j.axis; break;
      case JointType::Prismatic: j.S.col(0).head<3>() = j.axis; break;
      case JointType::Spherical: j.S.block<3, 3>(3, 0).setIdentity(); break;
      case JointType::Free: j.S.setIdentity(); break;
      case JointType::Hard:
      default: break;
    }
    // a rotation w about the joint origin moves the link origin, p_JL away, at w x p_JL
    for (int c = 0; c < j.nv; ++c) j.S.col(c).head<3>() += Vec3(j.S.col(c).tail<3>()).cross(j.p_JL);
  }
  m.nq = q_offset;
  m.nv = v_offset;
  m.root_nv = m.joints[0].nv;
  // the DOFs' tree: within a joint a chain, its first DOF below the nearest moving ancestor's last
  m.dof_parent.assign(m.nv, -1);
  for (int i = 0; i < n; ++i) {
    const JointModel& j = m.joints[i];
    if (j.nv == 0) continue;
    int above = m.parent[i];
    while (above >= 0 && m.joints[above].nv == 0) above = m.parent[above];
    m.dof_parent[j.v_offset] = above >= 0 ? m.joints[above].v_offset + m.joints[above].nv - 1 : -1;
    for (int c = 1; c < j.nv; ++c) m.dof_parent[j.v_offset + c] = j.v_offset + c - 1;
  }

  // links: mass properties from explicit values, or from the shape and density
  for (int i = 0; i < n; ++i) {
    const LinkDesc& L = desc.links[i];
    std::optional<ShapeGeometry> shape;
    if (L.shape) {
      validate_shape(*L.shape, source + ": " + at("links", i, "shape"));
      shape = scaled_shape(*L.shape, L.shape_scale, source + ": " + at("links", i, "shapeScale"));
    }
    if (L.center_of_mass && !L.center_of_mass->allFinite()) r.fail(at("links", i, "centerOfMass"), "must be finite");
    if (!L.link_from_shape.translation.allFinite() || !L.link_from_shape.rotation.coeffs().allFinite())
      r.fail(at("links", i, "shape"), "center and rotation must be finite");
    const SpatialTransform X_LS = SpatialTransform::from(Transform{L.link_from_shape.rotation.normalized(), L.link_from_shape.translation});
    // mass properties of the shape, expressed in the link frame
    auto shape_props = [&](real density) {
      MassProperties mp = shape_mass_properties(*shape, density);
      mp.center_of_mass = X_LS.R * mp.center_of_mass + X_LS.p;
      mp.inertia_about_com = X_LS.R * mp.inertia_about_com * X_LS.R.transpose();
      return mp;
    };
    SpatialInertia& I = m.inertia[i];
    // a massless link welded below another (a frame such as a fingertip or a flange) adds
    // nothing to the body it is merged into; moving links need mass
    const bool massless_weld = L.mass && *L.mass == 0 && i > 0 && desc.joints[i].type == JointType::Hard;
    if (massless_weld) {
      if (L.moment_of_inertia)
        for (real c : *L.moment_of_inertia)
          if (c != 0) r.fail(at("links", i, "momentOfInertia"), "must be zero on a massless link (mass 0), got " + num(c));
      I.mass = 0;
      I.com = L.center_of_mass.value_or(Vec3::Zero());
      I.inertia_com.setZero();
    } else if (L.mass) {
      if (!std::isfinite(*L.mass) || *L.mass <= 0)
        r.fail(at("links", i, "mass"), "must be a positive finite number, got " + num(*L.mass) +
                                           (*L.mass == 0 ? " (a massless link must hang from a Hard joint, which merges it into its parent)" : ""));
      I.mass = *L.mass;
      if (L.moment_of_inertia) {
        const auto& c = *L.moment_of_inertia;
        I.inertia_com << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
        I.com = L.center_of_mass.value_or(Vec3::Zero());
      } else if (shape && !std::holds_alternative<PlaneShape>(*shape)) {
        MassProperties mp = shape_props(1);
        I.com = L.center_of_mass.value_or(mp.center_of_mass);
        I.inertia_com = mp.inertia_about_com * (I.mass / mp.mass);
      } else {
        r.fail(at("links", i, "momentOfInertia"), "required when the link has a mass but no bounded shape");
      }
    } else {
      if (L.moment_of_inertia) r.fail(at("links", i, "mass"), "required when momentOfInertia is given");
      if (!shape || std::holds_alternative<PlaneShape>(*shape))
        r.fail(at("links", i, "mass"), "required: the link has no bounded shape to compute it from");
      const real density = L.density.value_or(real(1000));
      if (!std::isfinite(density) || density <= 0) r.fail(at("links", i, "density"), "must be a positive finite number, got " + num(density));
      MassProperties mp = shape_props(density);
      I.mass = mp.mass;
      I.com = L.center_of_mass.value_or(mp.center_of_mass);
      I.inertia_com = mp.inertia_about_com;
    }
    if (!massless_weld) check_inertia(I.inertia_com, r, at("links", i, "momentOfInertia"));
    m.has_gravity[i] = L.has_gravity;
    // contact surface
    if (L.layer < 0 || L.layer > 63) r.fail(at("links", i, "layer"), "must be between 0 and 63, got " + std::to_string(L.layer));
    validate(L.contact, source + ": " + at("links", i, "contact"));
    const ContactMaterial cm = contact_material(L.contact);
    auto add_collider = [&](const ShapeGeometry& g, const SpatialTransform& X) {
      LinkCollider c;
      c.link = i;
      c.shape = g;
      c.X_LS = X;
      c.material = cm;
      c.layer = L.layer;
      c.samples_S = shape_surface_samples(g);
      c.aabb_S = shape_local_aabb(g);
      m.colliders.push_back(std::move(c));
    };
    if (shape && L.collider_type != "None") add_collider(*shape, X_LS);
    // compound collision: the link's further shapes, each at its own pose
    for (size_t k = 0; k < L.extra_shapes.size(); ++k) {
      const LinkShapeDesc& e = L.extra_shapes[k];
      const std::string field = at("links", i, "extraShapes") + "[" + std::to_string(k) + "]";
      validate_shape(e.shape, source + ": " + field + ".shape");
      check_transform(e.link_from_shape, r, field + ".linkFromShape");
      if (L.collider_type != "None")
        add_collider(e.shape, SpatialTransform::from(Transform{e.link_from_shape.rotation.normalized(), e.link_from_shape.translation}));
    }
  }

  for (size_t k = 0; k < desc.contact_overrides.size(); ++k) {
    const ContactOverride& o = desc.contact_overrides[k];
    auto index_of = [&](const std::string& name, const char* field) {
      for (int i = 0; i < n; ++i)
        if (m.link_names[i] == name) return i;
      r.fail(at("contactOverrides", k, field), "no link named '" + name + "'");
    };
    const int a = index_of(o.link_a, "linkA"), b = index_of(o.link_b, "linkB");
    m.contact_overrides[{std::min(a, b), std::max(a, b)}] = o.enable;
  }

  const int pose_size = m.nv - m.root_nv;
  if (!desc.default_pose.empty() && static_cast<int>(desc.default_pose.size()) != pose_size)
    r.fail("defaultPose", "expected " + std::to_string(pose_size) + " values (the DOFs after the root joint), got " +
                              std::to_string(desc.default_pose.size()));
  for (size_t k = 0; k < desc.default_pose.size(); ++k)
    if (!std::isfinite(desc.default_pose[k])) r.fail(at("defaultPose", k), "must be finite");
  // couplings, then the two-joint linear transmissions as couplings
  auto add_coupling = [&](const JointCoupling& c, const std::string& list, size_t k) {
    auto one_dof_joint = [&](const std::string& name, const char* field) {
      for (int i = 0; i < n; ++i)
        if (m.joint_names[i] == name) {
          if (m.joints[i].type != JointType::Revolute && m.joints[i].type != JointType::Prismatic)
            r.fail(at(list.c_str(), k, field), "joint '" + name + "' is " + joint_type_name(m.joints[i].type) +
                                                    "; couplings join revolute and prismatic joints");
          return i;
        }
      r.fail(at(list.c_str(), k, field), "no joint named '" + name + "'");
    };
    const int f = one_dof_joint(c.joint, "joint"), l = one_dof_joint(c.leader, "leader");
    if (f == l) r.fail(at(list.c_str(), k, "leader"), "a joint cannot follow itself");
    if (!std::isfinite(c.ratio) || !std::isfinite(c.offset)) r.fail(at(list.c_str(), k, "ratio"), "ratio and offset must be finite");
    m.couplings.push_back({m.joints[f].v_offset, m.joints[l].v_offset, m.joints[f].q_offset, m.joints[l].q_offset, c.ratio, c.offset});
  };
  for (size_t k = 0; k < desc.couplings.size(); ++k) add_coupling(desc.couplings[k], "couplings", k);
  for (size_t k = 0; k < desc.linear_transmissions.size(); ++k) {
    const LinearTransmission& t = desc.linear_transmissions[k];
    if (t.joint_indices.size() != 2) continue;  // not built yet (the file's reader warned)
    const std::string where = source + ": linearTransmissions[" + std::to_string(k) + "]";
    add_coupling(coupling_of(t, desc.joints, where), "linearTransmissions", k);
  }
  for (size_t k = 0; k < desc.fixed_tendons.size(); ++k) m.tendons.push_back(tendon_model(desc.fixed_tendons[k], m, r, k));
  m.desc = desc;
  merge_welded_links(m);
  // every body that moves carries mass once welded links are merged into it
  for (int i : m.dynamics_order)
    if (m.joints[i].nv > 0 && !(m.dynamics_inertia[i].mass > 0))
      r.fail(at("links", i, "mass"), "the body of link '" + m.link_names[i] + "' (with the links welded to it) has no mass, but its joint moves");
  m.rigid_body.assign(n, 0);
  for (int i : m.order) m.rigid_body[i] = m.parent[i] >= 0 && m.joints[i].nv == 0 ? m.rigid_body[m.parent[i]] : i;
  return m;
}

void q_from_pose(const ArticulationModel& model, const real* pose, bool skip_root, VecX& q) {
  int k = 0;
  for (int i = 0; i < model.num_links; ++i) {
    const JointModel& j = model.joints[i];
    if (i == 0 && skip_root) continue;
    real* qi = q.data() + j.q_offset;
    switch (j.type) {
      case JointType::Hard:
      default: break;
      case JointType::Revolute:
      case JointType::Prismatic: qi[0] = pose[k]; break;
      case JointType::Spherical: {
        Quat quat = quat_exp(Vec3(pose[k], pose[k + 1], pose[k + 2]));
        map4(qi) = quat.coeffs();
        break;
      }
      case JointType::Free: {
        map3(qi) = Vec3(pose[k], pose[k + 1], pose[k + 2]);
        Quat quat = quat_exp(Vec3(pose[k + 3], pose[k + 4], pose[k + 5]));
        map4(qi + 3) = quat.coeffs();
        break;
      }
    }
    k += j.nv;
  }
}

void pose_from_q(const ArticulationModel& model, const VecX& q, real* pose) {
  for (int i = 0; i < model.num_links; ++i) {
    const JointModel& j = model.joints[i];
    const real* qi = q.data() + j.q_offset;
    real* out = pose + j.v_offset;
    switch (j.type) {
      case JointType::Hard:
      default: break;
      case JointType::Revolute:
      case JointType::Prismatic: out[0] = qi[0]; break;
      case JointType::Spherical: map3(out) = quat_log(Quat(qi[3], qi[0], qi[1], qi[2])); break;
      case JointType::Free:
        map3(out) = Vec3(qi[0], qi[1], qi[2]);
        map3(out + 3) = quat_log(Quat(qi[6], qi[3], qi[4], qi[5]));
        break;
    }
  }
}

ArticulationState initial_state(const ArticulationModel& model) {
  ArticulationState s;
  s.q = VecX::Zero(model.nq);
  s.v = VecX::Zero(model.nv);
  s.tau_external = VecX::Zero(model.nv);
  s.drives.assign(model.nv, JointDrive{});
  s.link_drives.assign(model.num_links, LinkDrive{});
  s.transmission_actuators.assign(model.transmissions.size(), TransmissionActuator{});
  Transform X_WR = model.desc.world_from_root;
  X_WR.rotation.normalize();
  s.X_W_base = SpatialTransform::from(X_WR);
  // identity rotations for quaternion coordinates
  for (const JointModel& j : model.joints) {
    if (j.type == JointType::Spherical) s.q[j.q_offset + 3] = 1;
    if (j.type == JointType::Free) s.q[j.q_offset + 6] = 1;
  }
  if (!model.desc.default_pose.empty()) q_from_pose(model, model.desc.default_pose.data(), true, s.q);
  return s;
}

bool link_moves(const ArticulationModel& model, int link) {
  for (int l = link; l >= 0; l = model.parent[l])
    if (model.joints[l].nv > 0) return true;
  return false;
}

LinkPairContact link_pair_contact(const ArticulationModel& model, int link_a, int link_b) {
  const int a = model.rigid_body[link_a], b = model.rigid_body[link_b];
  if (a == b) return LinkPairContact::Never;
  const bool joined = (model.parent[b] >= 0 && model.rigid_body[model.parent[b]] == a) ||
                      (model.parent[a] >= 0 && model.rigid_body[model.parent[a]] == b);
  return joined ? LinkPairContact::OffByDefault : LinkPairContact::OnByDefault;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
