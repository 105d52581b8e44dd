// Python values as JSON: what the JSON-reading parts of the API (prefabs, bot descriptions)
// receive from dicts and lists.

#include <nanobind/stl/string.h>

#include "bind_common.h"

namespace superdex::python {

nlohmann::json to_json(nb::handle obj, const std::string& path) {
  if (obj.is_none()) return nullptr;
  if (nb::isinstance<nb::bool_>(obj)) return nb::cast<bool>(obj);
  if (nb::isinstance<nb::int_>(obj)) return nb::cast<long long>(obj);
  if (nb::isinstance<nb::float_>(obj)) return nb::cast<double>(obj);
  if (nb::isinstance<nb::str>(obj)) return nb::cast<std::string>(obj);
  if (nb::isinstance<nb::dict>(obj)) {
    nlohmann::json out = nlohmann::json::object();
    for (auto [k, v] : nb::cast<nb::dict>(obj)) {
      if (!nb::isinstance<nb::str>(k)) throw Error(path + ": dict keys must be strings");
      const std::string key = nb::cast<std::string>(k);
      out[key] = to_json(v, path + "." + key);
    }
    return out;
  }
  if (nb::isinstance<nb::list>(obj) || nb::isinstance<nb::tuple>(obj) || nb::hasattr(obj, "tolist")) {
    nb::object seq = nb::hasattr(obj, "tolist") ? obj.attr("tolist")() : nb::borrow(obj);
    if (!nb::isinstance<nb::list>(seq) && !nb::isinstance<nb::tuple>(seq)) return to_json(seq, path);
    nlohmann::json out = nlohmann::json::array();
    size_t i = 0;
    for (nb::handle item : seq) out.push_back(to_json(item, path + "[" + std::to_string(i++) + "]"));
    return out;
  }
  if (nb::hasattr(obj, "__float__")) return nb::cast<double>(obj.attr("__float__")());
  throw Error(path + ": cannot be read as JSON (got " + std::string(nb::inst_name(obj).c_str()) + ")");
}

}  // namespace superdex::python
