#pragma once
// The contact rows of one island solve, after its joint rows: per contact, three rows
// R_C^T (J_a(p) - J_b(p)) in J (frame R_C: contact_frame of the normal), and its frictional
// constraint block, regularised by the estimate of its Delassus block's diagonal.

#include "island/island_jacobian.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class ContactRows {
 public:
  // Starts with no contact frame (w.frames); the island's link Jacobians are reset once per step
  // (reset_link_jacobians).
  ContactRows(const IslandInputs& in, IslandWorkspace& w, IslandJacobian& J);

  // The rigid contacts that take part (w.solved_contacts): a link (side a) against a link (side b).
  void add_rigid();
  // The soft contacts: a point moving with up to three nodes of a full or reduced soft body by
  // barycentric weights (side a) against a link (side b).
  void add_soft();

 private:
  void add_link_side(int body, int link, const Vec3& p_W, const Mat3& R_C, real scale, Vec3& W_diag, real& vn_free);
  void add_skin_side(const Contact& c, const Mat3& R_C, Vec3& W_diag, real& vn_free);
  void add_reduced_side(const ReducedVariables& rv, const SoftContact& c, const Mat3& R_C, Vec3& W_diag, real& vn_free);
  void add_node_side(const SoftContact& c, const Mat3& R_C, Vec3& W_diag, real& vn_free);
  void push_contact_block(const ContactMaterial& material, real phi, const Vec3& W_diag, real vn_free);

  const IslandInputs& in_;
  IslandWorkspace& w_;
  IslandJacobian& J_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
