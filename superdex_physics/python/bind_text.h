#pragma once
// Text forms of values: the shortest decimal that reads back to the same number ("4", "0.1"),
// and compact JSON with sorted keys, the form str() gives structs ('{"max":[4,5,6],"min":[1,2,3]}').

#include <charconv>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

namespace superdex::python {

// Shortest round-trip text of a float or double; integral values without a fraction.
template <class S>
std::string number_text(S x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), x);
  return std::string(buf, r.ptr);
}

// A number as JSON: integral values as integers, others as the double that the shortest text of
// the value reads back as, so that a float 0.1 prints as 0.1 and 4.0 as 4.
template <class S>
nlohmann::json number_json(S x) {
  if constexpr (std::is_integral_v<S>) {
    return x;
  } else {
    if (std::isfinite(x) && x == std::trunc(x) && std::abs(x) < S(1e15)) return static_cast<long long>(x);
    if (!std::isfinite(x)) return static_cast<double>(x);
    return std::stod(number_text(x));
  }
}

// A vector of N numbers as a JSON array.
template <class V>
nlohmann::json vector_json(const V& v) {
  nlohmann::json a = nlohmann::json::array();
  for (int i = 0; i < static_cast<int>(v.size()); ++i) a.push_back(number_json(v[i]));
  return a;
}

// "[4, 5, 6]"
template <class V>
std::string vector_text(const V& v) {
  std::string s = "[";
  for (int i = 0; i < static_cast<int>(v.size()); ++i) s += (i ? ", " : "") + number_text(v[i]);
  return s + "]";
}

}  // namespace superdex::python
