// Rod actors (Scene::create_rod_actor): a polyline model turned into a soft body whose elements are
// rod elements (rod_model.h), with one ghost node per element for its material frame.

#include <algorithm>
#include <cmath>

#include "scene/scene_data.h"
#include "soft/soft_body.h"
#include "superdex/physics/error.h"
#include "superdex/physics/model.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The rod's soft body: polyline nodes (local, placed at X_WL) joined in order, element e from node
// e to node e + 1 (the last one back to node 0 when the loop is closed), each with its frame axis.
std::unique_ptr<SoftBody> build_rod_body(const std::string& name, const MeshData& mesh, const std::vector<real>& axes,
                                         const RodMaterialParams& mat, const Transform& X_WL, const std::string& where) {
  const int n = mesh.num_nodes();
  // a polyline without connectivity joins its nodes in order
  const int ne = mesh.connectivity.empty() ? n - 1 : mesh.num_elements();
  if (n < 2 || ne < 1) throw Error(where + ".shape: a rod needs at least 2 nodes and 1 element, the polyline has " + std::to_string(n) +
                                   " nodes and " + std::to_string(ne) + " elements");
  const bool closed = ne == n && n >= 3 && !mesh.connectivity.empty();
  if (ne != n - 1 && !closed)
    throw Error(where + ".shape: the polyline must be one chain of its nodes in order (" + std::to_string(n - 1) + " elements, or " +
                std::to_string(n) + " for a closed loop), it has " + std::to_string(ne) + " elements");
  for (int e = 0; e < ne && !mesh.connectivity.empty(); ++e) {
    const int a = mesh.connectivity[2 * e], b = mesh.connectivity[2 * e + 1];
    if (a != e || b != (e + 1) % n)
      throw Error(where + ".shape: element " + std::to_string(e) + " joins nodes " + std::to_string(a) + " and " + std::to_string(b) +
                  "; a rod's element e must join node e to node " + (closed && e == ne - 1 ? std::string("0") : std::to_string(e + 1)));
  }
  if (static_cast<int>(axes.size()) != 3 * ne)
    throw Error(where + ".shape: element_frame_axes has " + std::to_string(axes.size()) + " values, expected 3 per element (" +
                std::to_string(3 * ne) + ")");
  auto rod = std::make_shared<RodModel>();
  rod->num_nodes = n;
  rod->closed = closed;
  rod->stiffness = Vec3(mat.flexural_stiffness[0], mat.flexural_stiffness[1], mat.torsional_stiffness);
  // world rest positions of the polyline, then of the ghosts
  VecX x(3 * (n + ne));
  for (int i = 0; i < n; ++i)
    x.segment<3>(3 * i) = X_WL * Vec3(mesh.coordinates[3 * i], mesh.coordinates[3 * i + 1], mesh.coordinates[3 * i + 2]);
  // the ghosts sit at least ten radii of gyration of the cross-section away, so that their mass
  // (the element's spin inertia) stays below 1 % of the element's
  const real gyration = std::sqrt(mat.linear_rotational_inertia / mat.linear_density);
  SoftBody* body = nullptr;
  auto owner = std::make_unique<SoftBody>();
  body = owner.get();
  SoftModel& m = body->model;
  m.node_mass = VecX::Zero(n + ne);
  for (int e = 0; e < ne; ++e) {
    RodElement el;
    el.nodes = {e, (e + 1) % n, n + e};
    const Vec3 xa = x.segment<3>(3 * el.nodes[0]), xb = x.segment<3>(3 * el.nodes[1]);
    el.rest_length = (xb - xa).norm();
    if (!(el.rest_length > 0))
      throw Error(where + ".shape: element " + std::to_string(e) + " has zero length (nodes " + std::to_string(el.nodes[0]) + " and " +
                  std::to_string(el.nodes[1]) + " coincide)");
    const Vec3 t = (xb - xa) / el.rest_length;
    const Vec3 axis = X_WL.rotation * Vec3(axes[3 * e], axes[3 * e + 1], axes[3 * e + 2]);
    const Vec3 u = axis - t * axis.dot(t);
    if (!(u.norm() > real(1e-6) * std::max(real(1), axis.norm())))
      throw Error(where + ".shape: element_frame_axes[" + std::to_string(e) + "] is zero or along the element");
    el.ghost_distance = std::max(el.rest_length, 10 * gyration);
    el.axial_stiffness = mat.axial_stiffness / el.rest_length;
    el.ghost_stiffness = mat.axial_stiffness / el.ghost_distance;
    x.segment<3>(3 * el.nodes[2]) = (xa + xb) / 2 + el.ghost_distance * u.normalized();
    // lumped masses: half the element's at each end; its spin inertia relative to its midpoint
    // (rod_spin_momentum), floored so that a rod without rotational inertia keeps a well-posed step
    const real element_mass = mat.linear_density * el.rest_length;
    el.spin_mass = std::max(mat.linear_rotational_inertia * el.rest_length / (el.ghost_distance * el.ghost_distance),
                            real(1e-6) * element_mass);
    m.node_mass[el.nodes[0]] += element_mass / 2;
    m.node_mass[el.nodes[1]] += element_mass / 2;
    m.total_mass += element_mass;
    rod->elements.push_back(el);
  }
  // bending and twisting between consecutive elements, from their rest frames
  for (int e = 0; e + 1 < ne || (closed && e < ne); ++e) {
    RodJoint j;
    j.e = e;
    j.f = (e + 1) % ne;
    j.voronoi_length = (rod->elements[j.e].rest_length + rod->elements[j.f].rest_length) / 2;
    j.rest_darboux = rod_darboux(rod_element_frame(*rod, j.e, x), rod_element_frame(*rod, j.f, x));
    rod->joints.push_back(j);
  }
  // the rest mesh in the actor frame (polyline nodes, then ghosts): what resets go back to
  auto rest = std::make_shared<TetMesh>();
  const Transform X_LW = X_WL.inverse();
  for (int i = 0; i < n + ne; ++i) rest->nodes.push_back(X_LW * Vec3(x.segment<3>(3 * i)));
  m.name = name;
  m.mesh = std::move(rest);
  m.rod = std::move(rod);
  m.alpha = mat.mass_damping_coefficient;
  m.beta = mat.stiffness_damping_coefficient;
  m.pinned.assign(n + ne, 0);
  m.pin_target = x;
  body->state.x = x;
  body->state.v = VecX::Zero(x.size());
  body->state.tau_external = VecX::Zero(x.size());
  return owner;
}

}  // namespace

ActorHandle Scene::create_rod_actor(const RodActorParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string where = "create_rod_actor('" + p.name + "'): params";
  validate(p, where);
  auto shape = shape_data(p.shape, where + ".shape");
  const ModelData* model = shape->model.get();
  if (!model || !model->mesh || model->mesh->nodes_per_element != 2)
    throw Error(where + ".shape: must be a polyline model (2 nodes per element): generate_tubular_rod_model_data, or a model file with one");
  if (!model->element_frame_axes) throw Error(where + ".shape: the polyline has no element_frame_axes (one axis per element, normal to it)");
  warn_unused_contact_fields(p.contact, where);
  Transform X = p.world_from_local;
  X.rotation.normalize();
  auto body = build_rod_body(p.name, *model->mesh, *model->element_frame_axes, p.material, X, where);
  body->X_WL = X;
  body->recentering.use_recentering = false;
  set_soft_actor_fields(s, *body, p.has_gravity, p.contact, p.layer, where);
  body->shape = std::move(shape);
  return add_soft_body(s, std::move(body));
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
