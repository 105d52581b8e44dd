// ControllerBasicJscPdParams: JSON text and `.superdex_controller` files.

#include <fstream>

#include "builtin_support.h"
#include "superdex/robotics/controller_basic_jsc_pd.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

const char* const kKeys[] = {"kp", "kd", "saturation", "deadband"};

std::vector<real>& field(ControllerBasicJscPdParams& p, int i) {
  std::vector<real>* fields[] = {&p.kp, &p.kd, &p.saturation, &p.deadband};
  return *fields[i];
}

}  // namespace

ControllerBasicJscPdParams ControllerBasicJscPdParams::from_json_text(const std::string& text, const std::string& where) {
  ComponentParams p(text, where);
  p.allow_only({"kp", "kd", "saturation", "deadband"});
  if (p.has("rate")) throw Error(p.at("rate") + ": not a gain (give the rate to the controller's configure)");
  ControllerBasicJscPdParams out;
  for (int i = 0; i < 4; ++i) {
    if (!p.has(kKeys[i])) continue;
    const auto& v = p.json().at(kKeys[i]);
    // a number, or a list of any length (its length is checked against the articulation later)
    const int n = v.is_array() ? static_cast<int>(v.size()) : 1;
    const VecX x = p.vector(kKeys[i], n, VecX());
    field(out, i).assign(x.data(), x.data() + x.size());
  }
  return out;
}

std::string ControllerBasicJscPdParams::to_json_text() const {
  nlohmann::json j = nlohmann::json::object();
  ControllerBasicJscPdParams copy = *this;
  for (int i = 0; i < 4; ++i)
    if (!field(copy, i).empty()) j[kKeys[i]] = field(copy, i);
  return j.dump(2);
}

ControllerBasicJscPdParams ControllerBasicJscPdParams::load_from_file(const std::string& path) {
  const auto first = path.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || path[first] == '{')
    throw Error("ControllerBasicJscPdParams.load_from_file: path: expected a file path, got '" + path + "'");
  return from_json_text(path, "ControllerBasicJscPdParams.load_from_file('" + path + "')");
}

void ControllerBasicJscPdParams::save_to_file(const std::string& path) const {
  std::ofstream out(path);
  if (!out) throw Error("ControllerBasicJscPdParams.save_to_file: path: cannot write '" + path + "'");
  out << to_json_text() << "\n";
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
