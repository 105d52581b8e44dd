#pragma once
// The convex-problem block of one frictional contact, shared by the island solver (rigid and
// articulated bodies) and soft bodies.

#include "solver/newton_solver.h"
#include "superdex/physics/shape.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Orthonormal contact frame [t1 t2 n] (columns) around the unit normal n.
Mat3 contact_frame(const Vec3& n);

// A FrictionalContact block for signed distance phi (m), the contact's effective compliance w
// (trace of its Delassus block / 3) and normal compliance w_nn (1/kg), and the normal velocity
// vn_free of the unconstrained motion (m/s). Compliant materials (stiffness > 0) follow SAP's
// spring-damper; near-rigid ones remove the predicted penetration within one step with the target
// compensated for the regularisation (for an isolated contact vn = vhat exactly), so that an
// impact does not overshoot into the surface and resting bodies do not sag.
ConstraintBlock frictional_contact_block(const ContactMaterial& material, real phi, real w, real w_nn, real vn_free,
                                         real dt, const StepSettings& params);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
