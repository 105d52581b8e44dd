// Numerical fault detection for Scene::step (step_guard.h).

#include "scene/step_guard.h"

#include <algorithm>
#include <sstream>

#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

bool all_finite(const std::vector<VecX>& xs) {
  return std::all_of(xs.begin(), xs.end(), [](const VecX& x) { return x.allFinite(); });
}
bool all_finite(const std::vector<Vec3>& xs) {
  return std::all_of(xs.begin(), xs.end(), [](const Vec3& x) { return x.allFinite(); });
}

}  // namespace

void StepGuard::add(ActorHandle actor, const std::string& name, const std::string& quantity, const std::string& detail) {
  // one fault per actor: the first quantity found bad (the others follow from it)
  for (const NumericalFault& f : faults_)
    if (f.actor == actor) return;
  NumericalFault f;
  f.actor = actor;
  f.quantity = quantity;
  f.message = "step: scene '" + s_.name + "', actor '" + name + "' (handle " + std::to_string(actor) + "): " + detail;
  faults_.push_back(std::move(f));
}

bool StepGuard::check_island(const Island& island, IslandSolution& sol) {
  const bool finite_v = all_finite(sol.v) && all_finite(sol.soft_v);
  const bool finite_f = all_finite(sol.contact_force) && all_finite(sol.soft_contact_force);
  std::string quantity, detail;
  if (!finite_v) {
    quantity = "velocities";
    detail = "velocities became non-finite (NaN or infinity)";
  } else if (!finite_f) {
    quantity = "contact forces";
    detail = "contact forces became non-finite (NaN or infinity)";
  } else if (sol.status == ConvergenceStatus::Diverged) {
    std::ostringstream os;
    os << "the solver diverged (scaled residual " << sol.residual << " after " << sol.iterations
       << " Newton iterations, beyond the divergence tolerances)";
    quantity = "convergence";
    detail = os.str();
  } else {
    return false;
  }
  const std::string advice = quantity == "convergence"
                                 ? "; reduce dt, or check forces, masses and stiffnesses"
                                 : "; check forces, masses, stiffnesses and dt";
  const std::string outcome = clamp() ? "; its island keeps its last good positions with zero velocity"
                                      : "; the scene keeps its last good state";
  for (int b : island.bodies) {
    const Articulation& a = *s_.articulations[b];
    add(a.handle, a.model.name, quantity, detail + outcome + advice);
  }
  for (int k : island.soft_bodies) {
    // a soft body's unknowns are its node velocities
    const SoftBody& body = *s_.soft_bodies[k];
    const std::string soft_quantity = quantity == "velocities" ? "node velocities" : quantity;
    add(body.handle, body.model.name, soft_quantity, (quantity == "velocities" ? "node " : "") + detail + outcome + advice);
  }
  if (!clamp()) return false;
  // clamp: the island's bodies stop where they are; no contact force is reported
  for (size_t j = 0; j < island.bodies.size(); ++j) sol.v[j].setZero(s_.articulations[island.bodies[j]]->model.nv);
  for (VecX& e : sol.drive_efforts) e.setZero();
  for (VecX& v : sol.soft_v) v.setZero();
  for (SoftState& st : sol.soft_reduced) st.q.resize(0);  // reduced bodies keep their state
  for (Vec3& f : sol.contact_force) f.setZero();
  for (Vec3& f : sol.soft_contact_force) f.setZero();
  return true;
}

bool StepGuard::check_articulation(int b, VecX& q, VecX& v) {
  if (q.allFinite() && v.allFinite()) return false;
  Articulation& a = *s_.articulations[b];
  const char* quantity = v.allFinite() ? "positions" : "velocities";
  add(a.handle, a.model.name, quantity,
      std::string(quantity) + " became non-finite (NaN or infinity)" +
          (clamp() ? "; it keeps its last good positions with zero velocity" : "; the scene keeps its last good state") +
          "; check forces, masses, stiffnesses and dt");
  if (!clamp()) return false;
  q = a.state.q;
  v.setZero(a.model.nv);
  return true;
}

void StepGuard::check_soft(int k, SoftState& next) {
  if (next.x.allFinite() && next.v.allFinite()) return;
  SoftBody& body = *s_.soft_bodies[k];
  const char* quantity = next.v.allFinite() ? "node positions" : "node velocities";
  add(body.handle, body.model.name, quantity,
      std::string(quantity) + " became non-finite (NaN or infinity)" +
          (clamp() ? "; it keeps its last good positions with zero velocity" : "; the scene keeps its last good state") +
          "; check the material, forces and dt");
  if (!clamp()) return;
  next = body.state;
  next.v.setZero();
}

void StepGuard::finish() {
  if (faults_.empty() || clamp()) {
    s_.last_faults = std::move(faults_);
    return;
  }
  std::string message = faults_[0].message;
  for (size_t i = 1; i < faults_.size() && i < 8; ++i) message += "\n" + faults_[i].message;
  if (faults_.size() > 8) message += "\n(" + std::to_string(faults_.size() - 8) + " more)";
  throw Error(message);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
