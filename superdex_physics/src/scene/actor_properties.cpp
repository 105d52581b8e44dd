// Properties of actors: contact params, collider type, mass properties, bounds, the shape they were
// made from, distances to their surface and their DOF values.

#include <algorithm>
#include <cmath>

#include "collision/collision_detection.h"
#include "collision/collision_geometry.h"
#include "multibody/dynamics.h"
#include "superdex/physics/inertia.h"
#include "multibody/kinematics.h"
#include "scene/actor_lookup.h"
#include "superdex/physics/log.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

const ActorRef& lookup_const(const SceneData& s, ActorHandle h, const char* what) {
  auto it = s.actors.find(h);
  if (it == s.actors.end()) throw Error(std::string(what) + ": " + describe(h) + " does not exist in scene '" + s.name + "'");
  return it->second;
}

// The dynamic rigid body (a rigid actor or a link) behind a handle; static ones are refused.
std::pair<Articulation*, int> dynamic_rigid(SceneData& s, ActorHandle h, const char* what) {
  ActorRef r = lookup(s, h, what);
  refuse_soft(r, h, what);
  if (r.link < 0 && !r.articulation->is_rigid)
    throw Error(std::string(what) + ": " + describe(h) + " is an articulated actor; call it on one of its link actors");
  if (r.articulation->is_static) throw Error(std::string(what) + ": " + describe(h) + " is static");
  return {r.articulation, std::max(r.link, 0)};
}

Real6 inertia_entries(const Mat3& I) { return (Real6() << I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2)).finished(); }

Mat3 inertia_matrix(const Real6& c) {
  Mat3 I;
  I << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
  return I;
}

// The soft body's centre of mass in the world (m).
Vec3 soft_com_W(const SoftBody& b) {
  Vec3 c = Vec3::Zero();
  for (int i = 0; i < b.model.node_mass.size(); ++i) c += b.model.node_mass[i] * b.state.x.segment<3>(3 * i);
  return c / b.model.total_mass;
}

// After a change of a link's inertia: the merged inertias the dynamics use.
void inertia_changed(Articulation& a) { merge_welded_links(a.model); }

}  // namespace

bool Scene::is_static(ActorHandle h) const {
  const ActorRef& r = lookup_const(scene_data(handle_), h, "is_static");
  return !r.soft && r.articulation->is_static;
}

ConvergenceStatus Scene::convergence_status(ActorHandle h) const {
  const ActorRef& r = lookup_const(scene_data(handle_), h, "get_convergence_status");
  return r.soft ? r.soft->convergence_status : r.articulation->convergence_status;
}

ContactParams Scene::contact_params(ActorHandle h) const {
  const ActorRef& r = lookup_const(scene_data(handle_), h, "get_contact_params");
  if (r.soft) return r.soft->contact_params;
  return r.articulation->links[std::max(r.link, 0)].contact;
}

void Scene::set_contact_params(ActorHandle h, const ContactParams& params) {
  SceneData& s = scene_data(handle_);
  ActorRef r = lookup(s, h, "set_contact_params");
  validate(params, "set_contact_params: params");
  const ContactMaterial m = contact_material(params);
  if (r.soft) {
    r.soft->contact_params = params;
    r.soft->model.contact = m;
    return;
  }
  Articulation& a = *r.articulation;
  for (int l = 0; l < a.model.num_links; ++l) {
    if (r.link >= 0 && l != r.link) continue;
    a.links[l].contact = params;
    for (LinkCollider& c : a.model.colliders)
      if (c.link == l) c.material = m;
  }
}

ColliderType Scene::collider_type(ActorHandle h) const {
  const ActorRef& r = lookup_const(scene_data(handle_), h, "get_collider_type");
  // a soft body's surface is found by the distance fields of others: it has no collider of its own
  if (r.soft) return ColliderType::None;
  const Articulation& a = *r.articulation;
  const int link = std::max(r.link, 0);
  const ColliderType given = a.links[link].collider_type;
  if (given != ColliderType::Auto) return given;
  for (const LinkCollider& c : a.model.colliders)
    if (c.link == link) {
      if (std::holds_alternative<SphereShape>(c.shape)) return ColliderType::Sphere;
      if (std::holds_alternative<PlaneShape>(c.shape)) return ColliderType::Plane;
      if (std::holds_alternative<BoxShape>(c.shape)) return ColliderType::Box;
      if (auto* m = std::get_if<MeshShape>(&c.shape); m && !m->sdf) return ColliderType::Mesh;
      return ColliderType::Sdf;
    }
  return ColliderType::None;
}

Real3 Scene::center_of_mass_local(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  ActorRef r = lookup(s, h, "get_rigid_center_of_mass_local");
  if (r.soft) return r.soft->X_WL.inverse() * soft_com_W(*r.soft);
  auto [a, link] = dynamic_rigid(s, h, "get_rigid_center_of_mass_local");
  return a->model.inertia[link].com;
}

TransformRT Scene::center_of_mass_transform(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  auto [a, link] = dynamic_rigid(s, h, "get_center_of_mass_transform");
  const SpatialTransform& X = a->kin.X_WL[link];
  return {Quat(X.R).normalized(), X.R * a->model.inertia[link].com + X.p};
}

void Scene::set_center_of_mass_transform(ActorHandle h, const TransformRT& X_WC) {
  SceneData& s = scene_data(handle_);
  auto [a, link] = dynamic_rigid(s, h, "set_center_of_mass_transform");
  if (!a->is_rigid) throw Error("set_center_of_mass_transform: " + describe(h) + " is a link actor; links follow their joints");
  const Quat q = X_WC.rotation.normalized();
  set_root_transform(h, Transform{q, X_WC.translation - q * a->model.inertia[link].com});
}

Real6 Scene::moment_of_inertia_local(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  auto [a, link] = dynamic_rigid(s, h, "get_rigid_moment_of_inertia_local");
  if (const auto& declared = a->links[link].declared_inertia) return *declared;
  return inertia_entries(a->model.inertia[link].inertia_com);
}

real Scene::density(ActorHandle h) const {
  const ActorRef& r = lookup_const(scene_data(handle_), h, "get_density");
  if (r.soft) return r.soft->material_params.density;
  if (r.link < 0 && !r.articulation->is_rigid)
    throw Error("get_density: " + describe(h) + " is an articulated actor; call it on one of its link actors");
  if (r.articulation->is_static) throw Error("get_density: " + describe(h) + " is static");
  return r.articulation->links[std::max(r.link, 0)].density;
}

void Scene::set_density(ActorHandle h, real density) {
  SceneData& s = scene_data(handle_);
  if (!(std::isfinite(density) && density > 0)) throw Error("set_density: density must be a positive finite number (kg/m^3), got " + std::to_string(density));
  ActorRef r = lookup(s, h, "set_density");
  if (r.soft) {
    SoftMaterialParams p = r.soft->material_params;
    p.density = density;
    set_soft_material_params(h, p);
    return;
  }
  auto [a, link] = dynamic_rigid(s, h, "set_density");
  LinkRecord& rec = a->links[link];
  if (!(rec.density > 0)) throw Error("set_density: " + describe(h) + " has no shape volume to scale its mass by");
  const real ratio = density / rec.density;
  SpatialInertia& I = a->model.inertia[link];
  I.mass *= ratio;
  I.inertia_com *= ratio;
  if (rec.declared_inertia) *rec.declared_inertia *= ratio;
  rec.density = density;
  inertia_changed(*a);
}

void Scene::set_inertia_properties(ActorHandle h, real mass, const Real3& com, const Real6& moi) {
  SceneData& s = scene_data(handle_);
  auto [a, link] = dynamic_rigid(s, h, "set_inertia_properties");
  if (!a->is_rigid) throw Error("set_inertia_properties: " + describe(h) + " is a link actor (only rigid actors)");
  if (!(std::isfinite(mass) && mass > 0)) throw Error("set_inertia_properties: mass must be a positive finite number, got " + std::to_string(mass));
  if (!com.allFinite()) throw Error("set_inertia_properties: center_of_mass must be finite");
  if (!moi.allFinite()) throw Error("set_inertia_properties: moment_of_inertia must be finite");
  SpatialInertia& I = a->model.inertia[link];
  I.mass = mass;
  I.com = com;
  I.inertia_com = inertia_matrix(moi);
  LinkRecord& rec = a->links[link];
  // an inertia that is not physical is reported as given and simulated as the nearest physical one
  rec.declared_inertia.reset();
  if (auto defect = inertia_defect(I.inertia_com)) {
    rec.declared_inertia = moi;
    I.inertia_com = nearest_physical_inertia(I.inertia_com);
    log_warning("set_inertia_properties: " + describe(h) + ": moment_of_inertia " + *defect + "; simulating the nearest physical inertia");
  }
  const ShapeGeometry* shape = rec.shape && rec.shape->geometry ? &*rec.shape->geometry : nullptr;
  if (shape && !std::holds_alternative<PlaneShape>(*shape)) rec.density = mass / shape_volume(*shape);
  inertia_changed(*a);
}

Aabb Scene::aabb_local(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  ActorRef r = lookup(s, h, "get_aabb_local");
  Bounds b;
  if (r.soft) {
    const Transform X_LW = r.soft->X_WL.inverse();
    for (Eigen::Index i = 0; i + 2 < 3 * r.soft->user_nodes(); i += 3) b.extend(X_LW * Vec3(r.soft->state.x.segment<3>(i)));
  } else {
    const Articulation& a = *r.articulation;
    // a link's colliders in its frame; a whole articulation's in its root link's frame
    const int frame = std::max(r.link, 0);
    const SpatialTransform X_FW = a.kin.X_WL[frame].inverse();
    for (const LinkCollider& c : a.model.colliders) {
      if (r.link >= 0 && c.link != r.link) continue;
      const SpatialTransform X_FS = X_FW * a.kin.X_WL[c.link] * c.X_LS;
      const Bounds w = world_bounds(c.aabb_S, X_FS);
      b.extend(w.min);
      b.extend(w.max);
    }
  }
  if (!(b.min.array() <= b.max.array()).all()) return Aabb{};
  return Aabb{b.min, b.max};
}

Aabb Scene::aabb_world(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  ActorRef r = lookup(s, h, "get_aabb_world");
  Bounds b;
  if (r.soft) {
    for (Eigen::Index i = 0; i + 2 < 3 * r.soft->user_nodes(); i += 3) b.extend(r.soft->state.x.segment<3>(i));
  } else {
    const Articulation& a = *r.articulation;
    for (const LinkCollider& c : a.model.colliders) {
      if (r.link >= 0 && c.link != r.link) continue;
      const Bounds w = world_bounds(c.aabb_S, a.kin.X_WL[c.link] * c.X_LS);
      b.extend(w.min);
      b.extend(w.max);
    }
    if (const ArticulationSkin* skin = skin_of(r))
      for (int i = 0; i < skin->num_nodes(); ++i) b.extend(skin_node_world(*skin, a.kin.X_WL, i));
  }
  if (!(b.min.array() <= b.max.array()).all()) return Aabb{};
  return Aabb{b.min, b.max};
}

ShapeHandle Scene::reference_shape(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  ActorRef r = lookup(s, h, "get_reference_shape");
  std::shared_ptr<const ShapeData> data = actor_shape(r);
  if (!data)
    throw Error("get_reference_shape: " + describe(h) +
                (r.soft || r.link >= 0 || r.articulation->is_rigid ? " has no shape" : " is an articulated actor: its link actors have shapes"));
  return add_shape_reference_to(std::move(data));
}

ShapeMeshes Scene::meshes(ActorHandle h) const {
  SceneData& s = scene_data(handle_);
  const ActorRef r = lookup(s, h, "get_mesh");
  // a skinned articulation's surface is its skin (every skin node is a surface node)
  if (const ArticulationSkin* skin = skin_of(r)) return {skin->mesh, skin->mesh, nullptr};
  const std::shared_ptr<const ShapeData> data = actor_shape(r);
  if (!data) return {};
  ShapeMeshes m = meshes_of(*data);
  // a soft body simulates the model's tetrahedra; a rigid body its surface
  if (!r.soft || !m.mesh) m.mesh = m.surface;
  return m;
}

std::vector<real> Scene::points_distance_to_surface(ActorHandle h, std::span<const Real3> points_W) const {
  SceneData& s = scene_data(handle_);
  ActorRef r = lookup(s, h, "get_points_distance_to_surface");
  if (r.soft) throw Error("get_points_distance_to_surface: " + describe(h) + " is a soft actor (it has no distance field)");
  const Articulation& a = *r.articulation;
  std::vector<real> out(points_W.size(), std::numeric_limits<real>::infinity());
  bool any = false;
  for (const LinkCollider& c : a.model.colliders) {
    if (r.link >= 0 && c.link != r.link) continue;
    any = true;
    const SpatialTransform X_SW = (a.kin.X_WL[c.link] * c.X_LS).inverse();
    for (size_t i = 0; i < points_W.size(); ++i)
      out[i] = std::min(out[i], shape_signed_distance(c.shape, Vec3(X_SW.R * points_W[i] + X_SW.p), nullptr));
  }
  if (!any) throw Error("get_points_distance_to_surface: " + describe(h) + " has no collider");
  return out;
}

std::vector<real> Scene::dof_values(ActorHandle h, std::span<const int> dofs) const {
  SceneData& s = scene_data(handle_);
  ActorRef r = lookup(s, h, "get_dof_values");
  VecX all;
  if (r.soft) {
    const std::vector<real> d = displacements(h);
    all = Eigen::Map<const VecX>(d.data(), static_cast<Eigen::Index>(d.size()));
  } else if (r.articulation->is_static) {
    throw Error("get_dof_values: " + describe(h) + " is static (it has no DOFs)");
  } else if (r.articulation->is_rigid) {
    // a rigid body's DOFs: its centre of mass position and its rotation vector
    const TransformRT X = center_of_mass_transform(h);
    const Eigen::AngleAxis<real> aa(X.rotation);
    all.resize(6);
    all << X.translation, aa.angle() * aa.axis();
  } else {
    if (r.link >= 0) throw Error("get_dof_values: " + describe(h) + " is a link actor; call it on its articulation");
    all = pose(h);
  }
  if (dofs.empty()) return std::vector<real>(all.data(), all.data() + all.size());
  std::vector<real> out;
  out.reserve(dofs.size());
  for (size_t k = 0; k < dofs.size(); ++k) {
    if (dofs[k] < 0 || dofs[k] >= all.size())
      throw Error("get_dof_values: dof_indices[" + std::to_string(k) + "] = " + std::to_string(dofs[k]) + " is out of range (" +
                  std::to_string(all.size()) + " DOFs)");
    out.push_back(all[dofs[k]]);
  }
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
