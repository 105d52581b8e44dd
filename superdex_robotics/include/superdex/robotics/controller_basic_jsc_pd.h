#pragma once
/// @file controller_basic_jsc_pd.h
/// BASIC_JSC_PD, the joint-space PD controller (src/controller_joint_pd.cpp): its gains as a
/// params struct that round-trips through JSON (`.superdex_controller` files), and the
/// interface through which a script reads and replaces them on a live controller.
///
/// Vectors are over the articulation's joint DOFs (bot DOF order without the root joint's
/// DOFs). A vector of one value is broadcast to every joint DOF; an empty vector means the
/// default of that field.

#include <string>
#include <vector>

#include "superdex/robotics/component.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct ControllerBasicJscPdParams {
  std::vector<real> kp;          ///< position gain, N m/rad (N/m); default 100
  std::vector<real> kd;          ///< damping gain, N m s/rad (N s/m); default 10
  std::vector<real> saturation;  ///< |effort| bound, N m (N); < 0: none (default -1)
  /// Position error magnitude removed before kp (rad or m); default 0. Damping always acts.
  std::vector<real> deadband;

  bool operator==(const ControllerBasicJscPdParams&) const = default;

  /// Reads a JSON object {"kp", "kd", "saturation", "deadband"} (each a number or a list); keys
  /// that are absent stay empty. Throws superdex::Error naming `where` and the key.
  static ControllerBasicJscPdParams from_json_text(const std::string& text, const std::string& where);
  std::string to_json_text() const;
  /// Reads / writes a `.superdex_controller` JSON file; errors name the file.
  static ControllerBasicJscPdParams load_from_file(const std::string& path);
  void save_to_file(const std::string& path) const;
};

/// The live BASIC_JSC_PD controller, as returned by a context's component lookup.
class ControllerBasicJscPd : public ControllerComponent {
 public:
  static constexpr const char* kTypeName = "BASIC_JSC_PD";
  /// The gains in use, one value per joint DOF.
  virtual ControllerBasicJscPdParams params() const = 0;
  /// Replaces the gains (empty vectors: defaults; one value: broadcast). Throws superdex::Error
  /// naming the field for a wrong length or a negative kp, kd or deadband.
  virtual void set_params(const ControllerBasicJscPdParams& params) = 0;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
