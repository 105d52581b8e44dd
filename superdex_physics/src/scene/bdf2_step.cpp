// BDF2 steps from extrapolated states (bdf2_step.h).

#include "scene/bdf2_step.h"

#include "multibody/kinematics.h"
#include "scene/scene_data.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

constexpr real kThird = real(1) / 3;

// 4/3 x - 1/3 x_prev
VecX extrapolated(const VecX& x, const VecX& x_prev) { return x + kThird * (x - x_prev); }

// The unit quaternion (x, y, z, w) at q moved on by a third of the rotation from q_prev to q
// (in q's own frame): q (q_prev^-1 q)^(1/3).
void extrapolate_rotation(real* q, const real* q_prev) {
  const Quat now(q[3], q[0], q[1], q[2]), before(q_prev[3], q_prev[0], q_prev[1], q_prev[2]);
  const Eigen::AngleAxis<real> step(before.conjugate() * now);
  const Quat next = (now * Quat(Eigen::AngleAxis<real>(step.angle() * kThird, step.axis()))).normalized();
  q[0] = next.x(), q[1] = next.y(), q[2] = next.z(), q[3] = next.w();
}

// The old target moved to where its motion to the target over 2/3 of the step keeps the rate it
// had over the whole step: target + 2/3 (old - target).
void keep_target_rates(ConstraintRecord& c) {
  constexpr real kTwoThirds = real(2) / 3;
  c.old_target_position = c.target_position + kTwoThirds * (c.old_target_position - c.target_position);
  c.old_target_value = c.target_value + kTwoThirds * (c.old_target_value - c.target_value);
  c.old_target_rotation = c.target_rotation.slerp(kTwoThirds, c.old_target_rotation);
  c.old_target_transform.translation =
      c.target_transform.translation + kTwoThirds * (c.old_target_transform.translation - c.target_transform.translation);
  c.old_target_transform.rotation = c.target_transform.rotation.slerp(kTwoThirds, c.old_target_transform.rotation);
}

void set_articulation(Articulation& a, const VecX& q, const VecX& v) {
  a.state.q = q;
  a.state.v = v;
  update_kinematics(a.model, a.state, a.kin);
}

}  // namespace

void bdf2_capture(const SceneData& s, Bdf2History& out) {
  out.bodies.resize(s.articulations.size());
  for (size_t i = 0; i < s.articulations.size(); ++i)
    out.bodies[i].q = s.articulations[i]->state.q, out.bodies[i].v = s.articulations[i]->state.v;
  out.softs.resize(s.soft_bodies.size());
  for (size_t i = 0; i < s.soft_bodies.size(); ++i) out.softs[i].q = s.soft_bodies[i]->state.x, out.softs[i].v = s.soft_bodies[i]->state.v;
}

bool bdf2_can_extrapolate(const SceneData& s, const Bdf2History& h, double dt) {
  if (!h.valid || h.dt != dt || h.bodies.size() != s.articulations.size() || h.softs.size() != s.soft_bodies.size()) return false;
  const auto same = [](const VecX& a, const VecX& b) { return a.size() == b.size() && a == b; };
  for (size_t i = 0; i < s.articulations.size(); ++i)
    if (!same(s.articulations[i]->state.q, h.bodies[i].q) || !same(s.articulations[i]->state.v, h.bodies[i].v)) return false;
  for (size_t i = 0; i < s.soft_bodies.size(); ++i) {
    const SoftBody& b = *s.soft_bodies[i];
    if (b.reduced || !same(b.state.x, h.softs[i].q) || !same(b.state.v, h.softs[i].v)) return false;
  }
  return true;
}

void bdf2_extrapolate(SceneData& s, const Bdf2History& h) {
  for (size_t i = 0; i < s.articulations.size(); ++i) {
    Articulation& a = *s.articulations[i];
    const Bdf2History::Body& b = h.bodies[i];
    VecX q = extrapolated(b.q, b.q_prev);
    // rotations: on the sphere, from the stored (unit) quaternions
    for (const JointModel& j : a.model.joints) {
      if (j.type == JointType::Spherical) {
        q.segment<4>(j.q_offset) = b.q.segment<4>(j.q_offset);
        extrapolate_rotation(q.data() + j.q_offset, b.q_prev.data() + j.q_offset);
      } else if (j.type == JointType::Free) {
        q.segment<4>(j.q_offset + 3) = b.q.segment<4>(j.q_offset + 3);
        extrapolate_rotation(q.data() + j.q_offset + 3, b.q_prev.data() + j.q_offset + 3);
      }
    }
    set_articulation(a, q, extrapolated(b.v, b.v_prev));
  }
  for (size_t i = 0; i < s.soft_bodies.size(); ++i) {
    SoftBody& body = *s.soft_bodies[i];
    body.state.x = extrapolated(h.softs[i].q, h.softs[i].q_prev);
    body.state.v = extrapolated(h.softs[i].v, h.softs[i].v_prev);
  }
  for (auto& [handle, c] : s.constraints) keep_target_rates(c);
}

void bdf2_restore(SceneData& s, const Bdf2History& start) {
  for (size_t i = 0; i < s.articulations.size() && i < start.bodies.size(); ++i)
    set_articulation(*s.articulations[i], start.bodies[i].q, start.bodies[i].v);
  for (size_t i = 0; i < s.soft_bodies.size() && i < start.softs.size(); ++i)
    s.soft_bodies[i]->state.x = start.softs[i].q, s.soft_bodies[i]->state.v = start.softs[i].v;
}

void bdf2_advance(const SceneData& s, double dt, Bdf2History& start, Bdf2History& h) {
  bdf2_capture(s, h);
  // the step may have created or destroyed nothing: the start matches body for body
  h.valid = start.bodies.size() == h.bodies.size() && start.softs.size() == h.softs.size();
  if (!h.valid) return;
  for (size_t i = 0; i < h.bodies.size(); ++i) h.bodies[i].q_prev.swap(start.bodies[i].q), h.bodies[i].v_prev.swap(start.bodies[i].v);
  for (size_t i = 0; i < h.softs.size(); ++i) h.softs[i].q_prev.swap(start.softs[i].q), h.softs[i].v_prev.swap(start.softs[i].v);
  h.dt = dt;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
