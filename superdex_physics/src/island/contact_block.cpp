// Frictional contact blocks (contact_block.h).

#include "island/contact_block.h"

#include <algorithm>
#include <cmath>

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
  if (!(w > 0)) {
    // a contact no DOF can move (a point on a hinge's axis, between a link and the welded one it
    // hangs from): no force can act through it; a passive block keeps it at zero
    blk.Rn = blk.R = 1;
    blk.vhat = 0;
    blk.bound = material.friction;
    return blk;
  }
  if (material.stiffness > 0) {
    // compliant contact (SAP): impulse = dt k (-(phi + dt vn) - tau_d vn), no stiffer than near-rigid
    const real tau_d = material.dissipation_time;
    blk.Rn = std::max(near_rigid * w, 1 / (dt * material.stiffness * (dt + tau_d)));
    blk.vhat = -phi / (dt + tau_d);
  } else {
    blk.Rn = near_rigid * w;
    // closing a gap within the step (phi > 0); out of penetration no faster than the bound
    const real vhat = phi < 0 ? std::min(-phi / dt, params.max_depenetration_speed) : -phi / dt;
    // the regularisation's correction, Rn / w_nn of the target's excess over the free motion, is at
    // most the excess itself: a contact that can hardly move along its normal (a nearly straight
    // leg's foot on a welded base, w_nn << w) would otherwise get a target many times too fast,
    // and one that cannot (w_nn = 0) a division by zero
    const real follow = w_nn > 0 ? std::min(blk.Rn / w_nn, real(1)) : real(0);
    blk.vhat = vhat + follow * (vhat - vn_free);
  }
  blk.R = params.friction_sigma * w;
  blk.bound = material.friction;
  return blk;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
