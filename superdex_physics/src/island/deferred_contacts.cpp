// Deferred rigid and soft contacts of an island solve (deferred_contacts.h).

#include "island/deferred_contacts.h"

#include <algorithm>

#include "island/link_jacobians.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The closing speed (m/s) a contact's block lets pass before acting: the gap over the step, and
// over the step and dissipation time of a compliant material (contact_block.cpp's targets).
real allowed_closing_speed(const ContactMaterial& m, real phi, real dt) {
  return m.stiffness > 0 ? phi / (dt + std::max<real>(m.dissipation_time, 0)) : phi / dt;
}

// The relative velocity (m/s, world) of a rigid contact's point on side a against side b when the
// island's bodies move at `v(body)` (a body's DOF velocities).
template <class Velocities>
Vec3 relative_velocity(const IslandInputs& in, const Contact& c, IslandWorkspace& w, LinkMotion motion, const Velocities& v) {
  return contact_point_velocity_a(in.s, c, motion, v(c.body_a), w) -
         link_point_velocity(in.s, c.body_b, c.link_b, c.p_W, motion, v(c.body_b), w);
}

// Whether a contact with a gap stays clear of acting at relative velocity v_rel: its normal
// velocity leaves the fraction `open` of the allowed closing open beyond friction's reach. A
// deferred contact's block has a target of at most -allowed (the free motion keeps it clear), so
// at open = 1 the block is inactive (vn >= vhat + mu |vt|, with the drift corrections too, which
// lower vhat by mu |vt|); the deferral asks for open = 1/2, room for the solve to move it.
bool stays_clear(const Contact& c, const Vec3& v_rel, real dt, real open) {
  if (!(c.phi > 0)) return false;
  const real vn = c.n_W.dot(v_rel);
  const real vt = (v_rel - vn * c.n_W).norm();
  return vn + open * allowed_closing_speed(c.material, c.phi, dt) >= c.material.friction * vt;
}

// A body's DOF velocities in the island's solution `out` (none for a body outside the island:
// one welded to the world).
const VecX& solution_velocity(const IslandSolution& out, const IslandWorkspace& w, int body) {
  static const VecX kNone;
  const int j = w.island_position[body];
  return j >= 0 ? out.v[j] : kNone;
}

}  // namespace

void select_rigid_contacts(const IslandInputs& in, IslandWorkspace& w) {
  const std::vector<int>& contacts = in.island.contacts;
  w.contact_takes_part.assign(contacts.size(), 1);
  if (!in.params.defer_separating_contacts) return;
  const auto current = [&](int body) -> const VecX& { return in.s.articulations[body]->state.v; };
  const auto free_motion = [&](int body) -> const VecX& { return in.terms[body].v_free; };
  for (size_t j = 0; j < contacts.size(); ++j) {
    const Contact& c = in.contacts[contacts[j]];
    if (!(c.phi > 0)) continue;
    w.contact_takes_part[j] = !(stays_clear(c, relative_velocity(in, c, w, LinkMotion::Current, current), in.dt, real(0.5)) &&
                                stays_clear(c, relative_velocity(in, c, w, LinkMotion::Free, free_motion), in.dt, real(0.5)));
  }
}

int admit_closing_rigid_contacts(const IslandInputs& in, const IslandSolution& out, IslandWorkspace& w) {
  int count = 0;
  const auto solution = [&](int body) -> const VecX& { return solution_velocity(out, w, body); };
  for (size_t j = 0; j < in.island.contacts.size(); ++j) {
    if (w.contact_takes_part[j]) continue;
    const Contact& c = in.contacts[in.island.contacts[j]];
    // only a contact the solution would make act changes it
    if (!stays_clear(c, relative_velocity(in, c, w, LinkMotion::Solution, solution), in.dt, 1)) w.contact_takes_part[j] = 1, ++count;
  }
  return count;
}

int admit_closing_soft_contacts(const IslandInputs& in, const IslandSolution& out, IslandWorkspace& w, std::vector<char>& admitted) {
  const Island& island = in.island;
  int count = 0;
  for (size_t j = 0; j < island.soft_contacts.size(); ++j) {
    const SoftContact& c = in.soft_contacts[island.soft_contacts[j]];
    if (admitted[j] || !soft_contact_deferred(c)) continue;
    const VecX& v_soft = out.soft_v[std::find(island.soft_bodies.begin(), island.soft_bodies.end(), c.soft) - island.soft_bodies.begin()];
    Vec3 v_point = Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      if (c.nodes[k] >= 0) v_point += c.weights[k] * v_soft.segment<3>(3 * c.nodes[k]);
    const VecX& v_body = solution_velocity(out, w, c.body);
    const real vn = c.n_W.dot(v_point - link_point_velocity(in.s, c.body, c.link, c.p_W, LinkMotion::Solution, v_body, w));
    if (vn < -allowed_closing_speed(c.material, c.phi, in.dt) / 2) admitted[j] = 1, ++count;
  }
  return count;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
