// An island solve's joint rows (drives, limits, joint constraints of its articulations): one row
// each in J, on its body's DOFs, and its constraint block.

#include <algorithm>

#include "island/island_jacobian.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void add_joint_rows(const IslandInputs& in, IslandWorkspace& w, IslandJacobian& J) {
  for (const auto [j, i] : w.solved_joint_rows) {
    const int b = in.island.bodies[j];
    const JointRow& jr = in.terms[b].joint_rows[i];
    J.begin_block(1);
    if (J.form() == IslandJacobian::Form::Bodies) {
      real* P = J.piece(j);
      if (jr.J.size() > 0) {
        std::copy(jr.J.data(), jr.J.data() + jr.J.size(), P);
      } else {
        P[jr.dof] = jr.sign;
      }
    } else if (jr.J.size() > 0) {
      for (Eigen::Index c = 0; c < jr.J.size(); ++c) J.add_column(w.body_offset[b] + static_cast<int>(c), &jr.J[c]);
    } else {
      J.add_column(w.body_offset[b] + jr.dof, &jr.sign);
    }
    J.end_block();
    ConstraintBlock blk = jr.block;
    if (jr.deferred) blk.R = deferred_compliance(in.terms[b], jr, in.params);
    blk.row = J.row++;
    w.rows.blocks.push_back(blk);
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
