// Frictional contact blocks (contact_block.h).

#include "island/contact_block.h"

#include <cmath>
#include <limits>

#include "multibody/articulation_step.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

Mat3 contact_frame(const Vec3& n) {
  const Vec3 helper = std::abs(n.x()) < real(0.9) ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 t1 = n.cross(helper).normalized();
  Mat3 R;
  R.col(0) = t1;
  R.col(1) = n.cross(t1);
  R.col(2) = n;
  return R;
}

ConstraintBlock frictional_contact_block(const ContactMaterial& material, real phi, real w, real w_nn, real vn_free,
                                         real dt, const StepSettings& params) {
  const real near_rigid = near_rigid_factor(params);
  ConstraintBlock blk;
  blk.kind = BlockKind::FrictionalContact;
  if (material.stiffness > 0) {
    // compliant contact (SAP): impulse = dt k (-(phi + dt vn) - tau_d vn), no stiffer than near-rigid
    const real tau_d = material.dissipation_time;
    blk.Rn = std::max(near_rigid * w, 1 / (dt * material.stiffness * (dt + tau_d)));
    blk.vhat = -phi / (dt + tau_d);
  } else {
    blk.Rn = near_rigid * w;
    // closing a gap within the step (phi > 0); out of penetration no faster than the bound
    const real vhat = phi < 0 ? std::min(-phi / dt, params.max_depenetration_speed) : -phi / dt;
    // a contact that cannot move along its normal (a straight leg's foot on a welded base: a
    // singular configuration, w_nn = 0) gets no regularisation correction: nothing could follow it
    const real follow = w_nn > std::numeric_limits<real>::epsilon() * w ? blk.Rn / w_nn : real(0);
    blk.vhat = vhat + follow * (vhat - vn_free);
  }
  blk.R = params.friction_sigma * w;
  blk.bound = material.friction;
  return blk;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
