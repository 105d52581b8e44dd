// Module constants, with SuperDex's names.

#include <numbers>

#include "bind_common.h"

namespace superdex::python {

void export_constants(nb::module_& m) {
  m.attr("REAL3_ZEROS") = Real3(0, 0, 0);
  m.attr("REAL3_ONES") = Real3(1, 1, 1);
  m.attr("REAL3_X_AXIS") = Real3(1, 0, 0);
  m.attr("REAL3_Y_AXIS") = Real3(0, 1, 0);
  m.attr("REAL3_Z_AXIS") = Real3(0, 0, 1);
  m.attr("MINUS2_PI_PLUS2_PI") = Real2(-2 * std::numbers::pi_v<real>, 2 * std::numbers::pi_v<real>);
  m.attr("UNIT_INTERVAL") = Real2(0, 1);
  m.attr("MESH_DATA_SPACE_DIM") = 3;
  m.attr("GRID_SDF_DEFAULT_BOUNDARY_PADDING") = kGridSdfDefaultBoundaryPadding;
  m.attr("DEFAULT_DENSITY") = kDefaultDensity;
  m.attr("DEFAULT_REL_STEP_TOL") = kDefaultRelStepTol;
  m.attr("AUTO_LINEAR_SOLVER_MAX_ITER") = kAutoLinearSolverMaxIter;
  m.attr("INVALID_HANDLE") = 0;
  m.attr("DEFAULT_GRAVITY") = Real3(kDefaultGravity);
  m.attr("TRANSFORM_RT_IDENTITY") = TransformRT();
  m.attr("QUATERNION_IDENTITY") = Quaternion::Identity();
  m.attr("GRID_SDF_PARAMS_DEFAULT") = GridSdfParams();
}

}  // namespace superdex::python
