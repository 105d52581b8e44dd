// The start of an island solve's J (island_jacobian.h): its form and empty storage.

#include "island/island_jacobian.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

IslandJacobian::IslandJacobian(const IslandInputs& in, const IslandLayout& layout, bool sparse, IslandWorkspace& w)
    : form_(sparse ? Form::Bodies : w.soft.empty() ? Form::Dense : Form::Rows), bodies_(w.J_bodies), rows_(w.J_rows), dense_(w.J_dense) {
  ConstraintRows& rows = w.rows;
  rows.blocks.clear();
  rows.blocks.reserve(layout.joint_rows + layout.num_contacts + layout.constraint_rows);
  if (form_ == Form::Bodies) {
    std::vector<int>& dofs = w.body_dofs;
    dofs.clear();
    for (int b : in.island.bodies) dofs.push_back(in.s.articulations[b]->model.nv);
    bodies_.reset(dofs);
  } else if (form_ == Form::Dense) {
    dense_.setZero(layout.joint_rows + 3 * layout.num_contacts + layout.constraint_rows, layout.n);
  } else {
    rows_.clear();
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
