// Actors made from SuperDex's params structs (RigidActorParams, SoftActorParams,
// ArticulatedActorParams): validated, turned into this engine's articulation and soft-body models.

#include <algorithm>
#include <cmath>

#include "collision/collision_geometry.h"
#include "multibody/joint_from_params.h"
#include "multibody/kinematics.h"
#include "scene/actor_records.h"
#include "scene/scene_data.h"
#include "soft/material_from_params.h"
#include "superdex/physics/error.h"
#include "superdex/physics/inertia.h"
#include "superdex/physics/log.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The collision geometry of a shape for a collider type, and its pose in the shape frame.
struct ColliderGeometry {
  std::optional<ShapeGeometry> shape;  // none for ColliderType::None
  Transform shape_from_collider;
};

ColliderGeometry collider_geometry(const ShapeGeometry& shape, ColliderType type, bool is_static, const std::string& where) {
  ColliderGeometry out;
  const bool plane = std::holds_alternative<PlaneShape>(shape);
  switch (type) {
    case ColliderType::None:
      return out;
    case ColliderType::Auto:
    case ColliderType::Mesh:
      out.shape = shape;
      return out;
    case ColliderType::Sdf:
      if (auto* m = std::get_if<MeshShape>(&shape); m && !m->sdf)
        throw Error(where + ".collider_type: SDF needs a closed mesh, and this shape's mesh is open");
      out.shape = shape;
      return out;
    case ColliderType::Plane:
      if (!plane) throw Error(where + ".collider_type: PLANE needs a plane shape (create_plane_shape)");
      if (!is_static) throw Error(where + ".collider_type: PLANE colliders are for static actors");
      out.shape = shape;
      return out;
    case ColliderType::Sphere:
    case ColliderType::Box: {
      if (plane) throw Error(where + ".collider_type: a plane shape is unbounded; use PLANE or AUTO");
      if (type == ColliderType::Sphere && std::holds_alternative<SphereShape>(shape)) {
        out.shape = shape;
        return out;
      }
      const Bounds b = shape_local_aabb(shape);
      const Vec3 center = real(0.5) * (b.min + b.max);
      out.shape_from_collider.translation = center;
      if (type == ColliderType::Box) {
        out.shape = BoxShape{real(0.5) * (b.max - b.min)};
      } else {
        // the ball about the box's centre through its farthest surface sample
        real r = 0;
        for (const Vec3& p : shape_surface_samples(shape)) r = std::max(r, (p - center).norm());
        out.shape = SphereShape{Vec3::Zero(), r};
      }
      return out;
    }
    case ColliderType::PointCloud:
      break;
  }
  throw Error(where + ".collider_type: POINT_CLOUD colliders are for rods and shells");
}

// One link of an articulation (or a rigid actor's only link) from the link fields of the params.
struct LinkInput {
  std::string name;
  std::shared_ptr<const ShapeData> shape;
  ColliderType collider_type = ColliderType::Auto;
  const ContactParams* contact = nullptr;
  int layer = 0;
  bool has_gravity = true;
  bool is_static = false;
  std::optional<real> density, mass;
  std::optional<Real3> center_of_mass;
  std::optional<Real6> moment_of_inertia;
  Vec3 joint_from_link = Vec3::Zero();  // link origin in its joint's frame (m)
};

// The link description, and the density a mass and a shape imply. A moment of inertia that is
// not physical is replaced by the nearest physical one, with a warning, and returned in `declared`.
LinkDesc link_desc(const LinkInput& in, const std::string& where, real& density_out, std::optional<Real6>& declared) {
  LinkDesc link;
  link.name = in.name;
  link.contact = *in.contact;
  link.layer = in.layer;
  link.has_gravity = in.has_gravity;
  const ShapeGeometry* shape = in.shape && in.shape->geometry ? &*in.shape->geometry : nullptr;
  const bool bounded = shape && !std::holds_alternative<PlaneShape>(*shape);
  if (in.is_static) {
    // welded bodies never move: their inertia only needs to be valid
    link.mass = 1;
    link.moment_of_inertia = std::array<real, 6>{1, 0, 0, 1, 0, 1};
    density_out = in.density.value_or(kDefaultDensity);
  } else {
    // the shape's own mass properties, per unit density, give what the params leave out
    const real volume = bounded ? shape_volume(*shape) : real(0);
    if (in.mass) {
      link.mass = *in.mass;
      density_out = volume > 0 ? *in.mass / volume : real(0);
    } else {
      density_out = in.density.value_or(kDefaultDensity);
      if (!bounded) throw Error(where + ".mass: required, since the link has no bounded shape to compute it from");
      link.mass = density_out * volume;
    }
    if (in.moment_of_inertia) {
      const Real6& c = *in.moment_of_inertia;
      Mat3 I;
      I << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
      if (auto defect = inertia_defect(I); defect && I.allFinite()) {
        I = nearest_physical_inertia(I);
        declared = c;
        log_warning(where + ".moment_of_inertia: " + *defect + "; simulating the nearest physical inertia [" + std::to_string(I(0, 0)) +
                    ", " + std::to_string(I(0, 1)) + ", " + std::to_string(I(0, 2)) + ", " + std::to_string(I(1, 1)) + ", " +
                    std::to_string(I(1, 2)) + ", " + std::to_string(I(2, 2)) + "]");
      }
      link.moment_of_inertia = std::array<real, 6>{I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2)};
    } else if (bounded) {
      const MassProperties mp = shape_mass_properties(*shape, 1);
      const Mat3 I = mp.inertia_about_com * (*link.mass / mp.mass);
      link.moment_of_inertia = std::array<real, 6>{I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2)};
    } else {
      throw Error(where + ".moment_of_inertia: required, since the link has no bounded shape to compute it from");
    }
    link.center_of_mass = in.center_of_mass ? *in.center_of_mass : bounded ? shape_mass_properties(*shape, 1).center_of_mass : Vec3::Zero();
  }
  link.joint_from_link = in.joint_from_link;
  if (shape) {
    const ColliderGeometry c = collider_geometry(*shape, in.collider_type, in.is_static, where);
    if (c.shape) {
      link.shape = *c.shape;
      link.link_from_shape = c.shape_from_collider;
    } else {
      link.collider_type = "None";
    }
  }
  return link;
}

}  // namespace

// Warns once per field when an actor is given a contact parameter this engine's contact model
// does not use (contact_params.h says which it uses).
void warn_unused_contact_fields(const ContactParams& p, const std::string& where) {
  const ContactParams d;
  auto check = [&](bool differs, const char* field) {
    if (differs)
      log_warning(where + ".contact." + field +
                  ": this engine's near-rigid contact does not use it (coulomb_friction_coefficient, contact_stiffness and dissipation_time_scale apply); it is kept as given");
  };
  check(p.penalty_coefficient != d.penalty_coefficient, "penalty_coefficient");
  check(p.penalty_smoothing_half_distance != d.penalty_smoothing_half_distance, "penalty_smoothing_half_distance");
  check(p.penalty_threshold_default != d.penalty_threshold_default, "penalty_threshold_default");
  check(p.penalty_threshold_extra_padding != d.penalty_threshold_extra_padding, "penalty_threshold_extra_padding");
  check(p.friction_with_collider_normal != d.friction_with_collider_normal, "friction_with_collider_normal");
  check(p.max_alignment_normals != d.max_alignment_normals, "max_alignment_normals");
  check(p.viscous_friction_coefficient != d.viscous_friction_coefficient, "viscous_friction_coefficient");
  check(p.friction_falloff_vel != d.friction_falloff_vel, "friction_falloff_vel");
  check(p.normal_viscous_damping_coefficient != d.normal_viscous_damping_coefficient, "normal_viscous_damping_coefficient");
  check(p.distance_error_bound != d.distance_error_bound, "distance_error_bound");
  check(p.obj_scale != d.obj_scale, "obj_scale");
  check(p.colliding_penalty_length_scale != d.colliding_penalty_length_scale, "colliding_penalty_length_scale");
}

namespace {

}  // namespace

ActorHandle Scene::create_rigid_actor(const RigidActorParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string where = "create_rigid_actor('" + p.name + "'): params";
  validate(p, where);
  auto shape = shape_data(p.shape, where + ".shape");
  if (!shape->geometry) throw Error(where + ".shape: it has no geometry a rigid body can carry");
  if (!p.is_static && std::holds_alternative<PlaneShape>(*shape->geometry))
    throw Error(where + ".shape: a plane is unbounded and can only carry a static actor (is_static=True)");
  warn_unused_contact_fields(p.contact, where);
  LinkInput in;
  // the body's one link and root joint take the actor's name (names are optional for actors)
  in.name = p.name.empty() ? "link_0" : p.name;
  in.shape = shape;
  in.collider_type = p.collider_type;
  in.contact = &p.contact;
  in.layer = contact_layer_index(s, p.layer, where + ".layer");
  in.has_gravity = p.has_gravity;
  in.is_static = p.is_static;
  in.density = p.density;
  in.mass = p.mass;
  in.center_of_mass = p.center_of_mass;
  in.moment_of_inertia = p.moment_of_inertia;
  real density = 0;
  ArticulationDesc desc;
  desc.name = p.name;
  desc.world_from_root = p.world_from_local;
  desc.world_from_root.rotation.normalize();
  std::optional<Real6> declared;
  desc.links = {link_desc(in, where, density, declared)};
  JointDesc joint;
  joint.name = p.name.empty() ? "root" : p.name + "_root";
  joint.type = p.is_static ? JointType::Hard : JointType::Free;
  desc.joints = {joint};
  auto a = std::make_unique<Articulation>();
  a->is_rigid = true;
  a->is_static = p.is_static;
  a->model = build_articulation_model(desc, where);
  a->links.push_back(LinkRecord{shape, p.contact, p.layer, density, p.collider_type, declared});
  const ActorHandle h = add_articulation(s, std::move(a));
  if (p.linear_velocity || p.angular_velocity)
    set_velocity(h, p.linear_velocity.value_or(Real3::Zero()), p.angular_velocity.value_or(Real3::Zero()));
  return h;
}

ActorHandle Scene::create_articulated_actor(const ArticulatedActorParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string where = "create_articulated_actor('" + p.name + "'): params";
  validate(p, where);
  ArticulationDesc desc;
  desc.name = p.name;
  desc.world_from_root = p.world_from_root;
  desc.world_from_root.rotation.normalize();
  auto a = std::make_unique<Articulation>();
  for (size_t i = 0; i < p.links.size(); ++i) {
    const ArticulatedLinkParams& l = p.links[i];
    const std::string lw = where + ".links[" + std::to_string(i) + "]";
    LinkInput in;
    in.name = l.name.empty() ? "link_" + std::to_string(i) : l.name;
    if (l.shape.is_valid()) in.shape = shape_data(l.shape, lw + ".shape");
    in.collider_type = l.collider_type;
    in.contact = &l.contact;
    in.layer = contact_layer_index(s, l.layer, lw + ".layer");
    in.has_gravity = l.has_gravity;
    in.density = l.density;
    in.mass = l.mass;
    in.center_of_mass = l.center_of_mass;
    in.moment_of_inertia = l.moment_of_inertia;
    in.joint_from_link = l.parent_joint_from_link.translation;
    if (in.shape && !in.shape->geometry) throw Error(lw + ".shape: it has no geometry a rigid link can carry");
    if (in.shape && std::holds_alternative<PlaneShape>(*in.shape->geometry)) throw Error(lw + ".shape: a plane cannot be a link's shape");
    warn_unused_contact_fields(l.contact, lw);
    real density = 0;
    std::optional<Real6> declared;
    LinkDesc link = link_desc(in, lw, density, declared);
    link.parent_link = l.parent_link;
    desc.links.push_back(std::move(link));
    desc.joints.push_back(joint_desc_from_params(p.joints[i], static_cast<int>(i)));
    a->links.push_back(LinkRecord{in.shape, l.contact, l.layer, density, l.collider_type, declared});
    a->joint_friction.push_back(p.joints[i].friction);
  }
  a->model = build_articulation_model(desc, where);
  if (p.skin) {
    auto shape = shape_data(p.skin->shape, where + ".skin.shape");
    // the links' rest poses in the root joint's parent frame: every joint at zero
    const VecX zero = VecX::Zero(a->model.nv);
    VecX q0 = VecX::Zero(a->model.nq);
    q_from_pose(a->model, zero.data(), false, q0);
    ArticulationKinematics rest;
    update_kinematics(a->model, q0, zero, SpatialTransform{}, rest);
    auto skin = build_articulation_skin(*p.skin, std::move(shape), a->model, rest.X_WL, where + ".skin.shape");
    skin->layer_index = contact_layer_index(s, p.skin->layer, where + ".skin.layer");
    skin->display = ActorHandle(next_handle());
    warn_unused_contact_fields(p.skin->contact, where + ".skin");
    a->skin = std::move(skin);
  }
  const ActorHandle h = add_articulation(s, std::move(a));
  if (p.joint_velocities) {
    const Articulation& art = *s.articulations.back();
    if (static_cast<int>(p.joint_velocities->size()) != art.model.nv) {
      destroy_actor(h);
      throw Error(where + ".joint_velocities: expected one value per DOF (" + std::to_string(art.model.nv) + "), got " +
                  std::to_string(p.joint_velocities->size()));
    }
    set_joint_velocities(h, Eigen::Map<const VecX>(p.joint_velocities->data(), art.model.nv));
  }
  return h;
}

ActorHandle Scene::create_soft_actor(const SoftActorParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string where = "create_soft_actor('" + p.name + "'): params";
  validate(p, where);
  if (!p.has_inertia) throw Error(where + ".has_inertia: quasi-static soft bodies are not available yet (keep it True)");
  if (!p.has_stress) throw Error(where + ".has_stress: soft bodies without elastic forces are not available yet (keep it True)");
  auto shape = shape_data(p.shape, where + ".shape");
  if (!shape->tet_mesh) throw Error(where + ".shape: must be a tetrahedral mesh (create_tet_mesh_shape, or a model file with tetrahedra)");
  warn_unused_contact_fields(p.contact, where);
  const SoftMaterial material = soft_material_from_params(p.material, *shape->tet_mesh);
  Transform X = p.world_from_local;
  X.rotation.normalize();
  auto body = build_soft_body(p.name, shape->tet_mesh, material, X, {}, where);
  body->model.contact = contact_material(p.contact);
  body->X_WL = X;
  body->material_params = p.material;
  set_soft_actor_fields(s, *body, p.has_gravity, p.contact, p.layer, where);
  body->shape = std::move(shape);
  return add_soft_body(s, std::move(body));
}

void set_soft_actor_fields(SceneData& s, SoftBody& body, bool has_gravity, const ContactParams& contact, const std::string& layer,
                           const std::string& where) {
  body.has_gravity = has_gravity;
  body.contact_params = contact;
  body.layer = layer;
  body.layer_index = contact_layer_index(s, layer, where + ".layer");
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
